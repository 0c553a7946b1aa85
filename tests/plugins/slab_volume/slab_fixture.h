// Test helpers for the slab_volume plugin: stone volume files written in code (two-part
// OpenEXR through OIIO, in the format of plugins/slab_volume/volume_file.h), the plugin
// loaded through the real plugin registry and host, instances bound from TOML exactly as
// a scene binds them, and thin wrappers that call the ABI functions.
#pragma once

#include "host/host.h"
#include "host/plugin_registry.h"
#include "host/shader_instance.h"

#include <patina/shading/vec.h>

#include <OpenImageIO/imageio.h>

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <unistd.h>

namespace slab_test {

namespace fs = std::filesystem;
using patina::shading::Vec2;
using patina::shading::Vec3;

/// What one voxel holds, in the order of the file contract.
struct Voxel {
    float density = 1.0f, crust = 0.0f, iron = 0.0f, salt = 0.0f;
};

/// A scratch folder for the files these tests write.
inline fs::path scratch_dir()
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "slab_volume";
    fs::create_directories(dir);
    return dir;
}

/// Writes a volume file: part 0 "voxels" (nx × ny·nz, channels named in the contract's
/// order density, crust, iron, salt — OpenEXR sorts them), part 1 "bounds" (3 × 3, one
/// channel). `voxel(i, j, k)` gives each voxel. `bounds_rows` overrides the third row
/// (voxel counts) to make inconsistent files.
inline fs::path write_volume(const std::string& name, int nx, int ny, int nz, Vec3 lo, Vec3 hi,
                             const std::function<Voxel(int, int, int)>& voxel,
                             const float* counts_override = nullptr)
{
    const fs::path path = scratch_dir() / (name + ".exr");
    OIIO::ImageSpec voxels(nx, ny * nz, 4, OIIO::TypeDesc::FLOAT);
    voxels.channelnames = {"density", "crust", "iron", "salt"};
    voxels.attribute("name", "voxels");
    OIIO::ImageSpec bounds(3, 3, 1, OIIO::TypeDesc::FLOAT);
    bounds.channelnames = {"value"};
    bounds.attribute("name", "bounds");
    bounds.full_width = voxels.width;
    bounds.full_height = voxels.height;

    std::vector<float> pixels(static_cast<size_t>(nx) * ny * nz * 4);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const Voxel v = voxel(i, j, k);
                float* p = &pixels[((static_cast<size_t>(k) * ny + j) * nx + i) * 4];
                p[0] = v.density;
                p[1] = v.crust;
                p[2] = v.iron;
                p[3] = v.salt;
            }
    const float n[3] = {static_cast<float>(nx), static_cast<float>(ny), static_cast<float>(nz)};
    const float* c = counts_override ? counts_override : n;
    const float b[9] = {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, c[0], c[1], c[2]};

    // Written under a name of this process's own, then renamed: tests that run side by side
    // (ctest -j) write the same volume, and one must never read another's half-written file.
    const fs::path tmp = scratch_dir() / (name + ".tmp" + std::to_string(::getpid()) + ".exr");
    auto out = OIIO::ImageOutput::create(tmp.string());
    const OIIO::ImageSpec specs[2] = {voxels, bounds};
    if (!out || !out->open(tmp.string(), 2, specs) ||
        !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) ||
        !out->open(tmp.string(), bounds, OIIO::ImageOutput::AppendSubimage) ||
        !out->write_image(OIIO::TypeDesc::FLOAT, b) || !out->close())
        throw std::runtime_error("cannot write test volume " + tmp.string() + ": " +
                                 (out ? out->geterror() : OIIO::geterror()));
    fs::rename(tmp, path);
    return path;
}

/// The same density and composition everywhere.
inline std::function<Voxel(int, int, int)> uniform(Voxel v)
{
    return [v](int, int, int) { return v; };
}

/// The registry with the slab_volume plugin loaded, on the default host.
inline const patina::PluginRegistry& registry()
{
    static const auto r = [] {
        auto reg = std::make_unique<patina::PluginRegistry>(patina::default_host().c_host());
        reg->load_file(fs::path(PATINA_TEST_PLUGIN_DIR) / "patina_slab_volume.so");
        return reg;
    }();
    return *r;
}

/// An instance of `shader` from TOML parameters (relative files resolve in scratch_dir()).
inline std::shared_ptr<patina::ShaderInstance> make(const std::string& shader,
                                                    const std::string& toml_params)
{
    const toml::table params = toml::parse(toml_params);
    patina::ParamSource source;
    source.file = "test.toml";
    source.base_dir = scratch_dir();
    return patina::create_shader_instance(registry(), shader, params, shader, source);
}

/// The error message of creating an instance, or "" when it succeeds.
inline std::string error_of(const std::string& shader, const std::string& toml_params)
{
    try {
        make(shader, toml_params);
    } catch (const std::exception& e) {
        return e.what();
    }
    return {};
}

/// Four wavelengths across the visible range.
inline PatinaWavelengths wavelengths()
{
    PatinaWavelengths wl{};
    wl.count = 4;
    const float l[4] = {450.0f, 520.0f, 600.0f, 680.0f};
    for (int i = 0; i < 4; ++i)
        wl.lambda_nm[i] = l[i];
    return wl;
}

using Spectrum = std::array<float, PATINA_MAX_WAVELENGTHS>;

/// The medium functions spelled as in the math.
class Medium {
public:
    explicit Medium(std::shared_ptr<patina::ShaderInstance> instance)
        : instance_(std::move(instance)), f_(instance_->medium()), wl_(wavelengths())
    {
    }
    struct Distance {
        bool scattered = false;
        float t = 0.0f;
        Spectrum weight{};
    };
    Distance sample_distance(Vec3 o, Vec3 d, float t_max, float u) const
    {
        Distance r;
        PatinaShadingContext ctx{};
        r.scattered = f_->sample_distance(instance_->get(), &ctx, o, d, t_max, u, &wl_, &r.t,
                                          r.weight.data()) != 0;
        return r;
    }
    float transmittance(Vec3 o, Vec3 d, float t, float u) const
    {
        Spectrum tr{};
        PatinaShadingContext ctx{};
        f_->transmittance(instance_->get(), &ctx, o, d, t, u, &wl_, tr.data());
        return tr[0];
    }
    float phase(Vec3 wo, Vec3 wi) const
    {
        Spectrum p{};
        return f_->phase_eval(instance_->get(), nullptr, wo, wi, &wl_, p.data());
    }
    float phase_sample(Vec3 wo, Vec2 u, Vec3* wi, Spectrum* p) const
    {
        PatinaVec3 w{};
        const float pdf = f_->phase_sample(instance_->get(), nullptr, wo, u, &wl_, &w, p->data());
        *wi = w;
        return pdf;
    }
    const PatinaWavelengths& wl() const { return wl_; }

private:
    std::shared_ptr<patina::ShaderInstance> instance_;
    const PatinaMediumFuncs* f_;
    PatinaWavelengths wl_;
};

} // namespace slab_test
