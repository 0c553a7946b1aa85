// Test helpers for the layered plugin: write a small patina stack (stack.toml with its
// [patina.materials] and constant thickness maps) into the test's scratch folder, load the
// built patina_layered.so (dlopen, RTLD_NOW | RTLD_LOCAL) with libpatina's host (OIIO
// textures), and call its shader as the math reads: f(wo, wi), pdf, sample, albedo.
#pragma once

#include "core/color_management.h"
#include "host/host.h"
#include "core/image_io.h"

#include <patina/abi.h>
#include <patina/shading/frame.h>
#include <patina/testing/bsdf_checks.h>
#include <patina/shading/vec.h>

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace patina::test {

namespace fs = std::filesystem;
using shading::Vec2;
using shading::Vec3;
using Spectrum = std::array<float, PATINA_MAX_WAVELENGTHS>;

/// A material with constant (or, with K_830, linearly varying) optics.
struct TestMaterial {
    std::string name;
    bool metal = false;
    float K = 0.0f;          ///< absorption per µm at 360 nm
    float K_830 = -1.0f;     ///< at 830 nm (< 0: same as K)
    float S = 1.0f;          ///< scattering per µm
    float specular = 0.04f;
    float roughness = 0.3f;
    float n = 0.27f, k = 3.4f; ///< metal (constant)
};

struct TestLayer {
    std::string material;
    float thickness_um = 0.0f;
};

struct TestStack {
    std::string base;
    std::vector<TestLayer> layers; ///< bottom to top
    std::vector<TestMaterial> materials;
};

inline fs::path scratch_dir(const std::string& name)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "layered" / name;
    fs::create_directories(dir);
    return dir;
}

inline std::string toml_array(float a, float b)
{
    std::ostringstream s;
    s.precision(9);
    s << "[" << a << ", " << b << "]";
    return s.str();
}

/// How write_stack stores the thicknesses: one map per layer (as patina-texgen writes them)
/// or one multi-channel map for the whole stack, layer l in channel n - 1 - l (named
/// "c<n-1-l>_layer<l+1>"; the layers refer to it by name, the bottom one by index).
enum class MapLayout { per_layer, one_map };

/// Writes `name`/stack.toml and 4x4 constant thickness maps; returns the stack.toml path.
inline fs::path write_stack(const std::string& name, const TestStack& stack,
                            MapLayout layout = MapLayout::per_layer)
{
    const fs::path dir = scratch_dir(name);
    std::ostringstream t;
    t.precision(9);
    const size_t n = stack.layers.size();
    if (layout == MapLayout::one_map && n > 0) {
        std::vector<float> texels(16 * n);
        std::vector<std::string> channels(n);
        for (size_t l = 0; l < n; ++l) {
            // OpenEXR stores channels sorted by name: the c<index> prefix keeps this order
            std::ostringstream name;
            name << "c" << n - 1 - l << "_layer" << l + 1;
            channels[n - 1 - l] = name.str();
            for (int p = 0; p < 16; ++p)
                texels[p * n + (n - 1 - l)] = stack.layers[l].thickness_um;
        }
        TextureOptions options;
        options.format = OIIO::TypeDesc::FLOAT;
        make_texture_atomic(dir / "thickness.exr", texels.data(), 4, 4, static_cast<int>(n),
                            channels, options);
        t << "[maps.thickness]\nfile = 'thickness.exr'\nchannels = [";
        for (size_t c = 0; c < n; ++c)
            t << (c ? ", '" : "'") << channels[c] << "'";
        t << "]\n\n[patina]\nbase = '" << stack.base << "'\nthickness_units = 'um'\n\n";
        for (size_t l = 0; l < n; ++l) {
            t << "[[patina.layers]]\nmaterial = '" << stack.layers[l].material
              << "'\nmap = 'thickness'\n";
            if (l == 0)
                t << "channel = " << n - 1 << "\n\n";
            else
                t << "channel = 'c" << n - 1 - l << "_layer" << l + 1 << "'\n\n";
        }
    }
    for (size_t l = 0; l < stack.layers.size() && layout == MapLayout::per_layer; ++l) {
        const std::string map = "layer" + std::to_string(l + 1);
        std::vector<float> texels(16, stack.layers[l].thickness_um);
        TextureOptions options;
        options.format = OIIO::TypeDesc::FLOAT;
        make_texture_atomic(dir / (map + ".exr"), texels.data(), 4, 4, 1, {"thickness"},
                            options);
        t << "[maps." << map << "]\nfile = '" << map << ".exr'\nchannels = ['thickness']\n\n";
    }
    if (layout == MapLayout::per_layer || n == 0)
        t << "[patina]\nbase = '" << stack.base << "'\nthickness_units = 'um'\n\n";
    for (size_t l = 0; l < stack.layers.size() && layout == MapLayout::per_layer; ++l)
        t << "[[patina.layers]]\nmaterial = '" << stack.layers[l].material << "'\nmap = 'layer"
          << l + 1 << "'\n\n";
    for (const TestMaterial& m : stack.materials) {
        t << "[patina.materials.\"" << m.name << "\"]\nmetal = " << (m.metal ? "true" : "false")
          << "\nroughness = " << m.roughness << "\nwavelengths_nm = [360.0, 830.0]\n"
          << "specular = " << toml_array(m.specular, m.specular) << "\n";
        if (m.metal)
            t << "n = " << toml_array(m.n, m.n) << "\nk = " << toml_array(m.k, m.k) << "\n\n";
        else
            t << "absorption_per_um = " << toml_array(m.K, m.K_830 < 0.0f ? m.K : m.K_830)
              << "\nscattering_per_um = " << toml_array(m.S, m.S) << "\n\n";
    }
    std::ofstream(dir / "stack.toml") << t.str();
    return dir / "stack.toml";
}

/// libpatina's host with the source tree's OCIO config.
inline Host& layered_host()
{
    static ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio");
    static Host host(colors, "layered plugin tests");
    return host;
}

inline const PatinaShaderDesc& layered_shader()
{
    static const PatinaShaderDesc* desc = [] {
        const std::string path = std::string(PATINA_TEST_PLUGIN_DIR) + "/patina_layered.so";
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle)
            throw std::runtime_error(std::string("dlopen failed: ") + dlerror());
        auto entry =
            reinterpret_cast<PatinaPluginEntryFn>(dlsym(handle, PATINA_PLUGIN_ENTRY_SYMBOL));
        if (!entry)
            throw std::runtime_error("no entry point in " + path);
        const PatinaPluginInfo* info = entry(layered_host().c_host());
        for (int i = 0; i < info->shader_count; ++i)
            if (std::strcmp(info->shaders[i].name, "layered_km") == 0)
                return &info->shaders[i];
        throw std::runtime_error("no shader layered_km in " + path);
    }();
    return *desc;
}

/// The wavelengths of a path, 8 of them over the visible range.
inline PatinaWavelengths test_wavelengths()
{
    PatinaWavelengths wl{};
    wl.count = 8;
    const float l[8] = {380.0f, 440.0f, 500.0f, 550.0f, 600.0f, 650.0f, 720.0f, 800.0f};
    for (int i = 0; i < 8; ++i)
        wl.lambda_nm[i] = l[i];
    return wl;
}

/// One layered_km instance at uv (0.5, 0.5).
class Layered {
public:
    explicit Layered(const fs::path& stack, const std::string& model = "km", int walk_samples = 64,
                     float thickness_scale = 1.0f)
    {
        const PatinaShaderDesc& d = layered_shader();
        std::vector<PatinaParamValue> v(d.param_count);
        const std::string path = stack.string();
        v[0].type = PATINA_PARAM_FILE;
        v[0].s = path.c_str();
        v[1].type = PATINA_PARAM_FLOAT;
        v[1].f = thickness_scale;
        v[2].type = PATINA_PARAM_STRING;
        v[2].s = model.c_str();
        v[3].type = PATINA_PARAM_INT;
        v[3].i = walk_samples;
        v[3].f = static_cast<float>(walk_samples);
        layered_host().take_errors();
        instance_ = d.create(layered_host().c_host(), v.data());
        for (const std::string& e : layered_host().take_errors())
            errors_ += e + "\n";
        ctx_.N = {0, 0, 1};
        ctx_.Ng = {0, 0, 1};
        ctx_.dPdu = {1, 0, 0};
        ctx_.dPdv = {0, 1, 0};
        ctx_.uv = {0.5f, 0.5f};
        wl_ = test_wavelengths();
    }
    ~Layered()
    {
        if (instance_)
            layered_shader().destroy(instance_);
    }
    Layered(const Layered&) = delete;
    Layered& operator=(const Layered&) = delete;

    explicit operator bool() const { return instance_ != nullptr; }
    const std::string& errors() const { return errors_; }
    void set_wavelengths(const PatinaWavelengths& wl) { wl_ = wl; }
    const PatinaWavelengths& wl() const { return wl_; }

    Spectrum f(Vec3 wo, Vec3 wi) const
    {
        Spectrum out{};
        layered_shader().bsdf->eval(instance_, &ctx_, wo, wi, &wl_, out.data());
        return out;
    }
    float pdf(Vec3 wo, Vec3 wi) const
    {
        return layered_shader().bsdf->pdf(instance_, &ctx_, wo, wi, &wl_);
    }
    bool sample(Vec3 wo, float u_lobe, Vec2 u, PatinaBsdfSample* out) const
    {
        *out = PatinaBsdfSample{};
        return layered_shader().bsdf->sample(instance_, &ctx_, wo, u_lobe, u, &wl_, out) != 0;
    }
    Spectrum albedo(Vec3 wo) const
    {
        Spectrum out{};
        layered_shader().bsdf->albedo(instance_, &ctx_, wo, &wl_, out.data());
        return out;
    }

    /// The instance as patina/testing/bsdf_checks.h calls it.
    test::BsdfCalls calls() const
    {
        test::BsdfCalls c(layered_shader().bsdf, instance_, wl_);
        c.ctx = ctx_;
        return c;
    }

    /// Directional albedo ∫ f(wo, wi) cos θi dωi per wavelength by the midpoint rule
    /// (patina/testing/bsdf_checks.h), theta_res cells over the upper hemisphere, pole +z
    /// (independent of the shader's sampling).
    Spectrum albedo_by_quadrature(Vec3 wo, int theta_res = 128) const
    {
        return to_floats(test::albedo_by_quadrature(calls(), wo, 2 * theta_res, {0.0f, 0.0f, 1.0f}));
    }

    /// Directional albedo per wavelength by importance sampling with the shader's own sampler
    /// (checked by the chi-square test) over n² stratified samples
    /// (patina/testing/bsdf_checks.h), accurate for sharp lobes where the quadrature is not.
    Spectrum albedo_by_sampling(Vec3 wo, int n = 64) const
    {
        return to_floats(test::albedo_by_sampling(calls(), wo, n));
    }

private:
    static Spectrum to_floats(const test::SpectrumValues& v)
    {
        Spectrum out{};
        for (size_t c = 0; c < out.size(); ++c)
            out[c] = static_cast<float>(v[c]);
        return out;
    }

    void* instance_ = nullptr;
    std::string errors_;
    PatinaShadingContext ctx_{};
    PatinaWavelengths wl_{};
};

inline Vec3 direction_deg(float theta_deg, float phi_deg)
{
    const float t = theta_deg * shading::kPi / 180.0f, p = phi_deg * shading::kPi / 180.0f;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

}  // namespace patina::test
