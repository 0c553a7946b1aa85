// Test helpers for the spectral_km plugin: load patina_spectral_km.so, write a fade stack of
// the in-code test material with a uniform dose map, and wrap an instance (created with the
// real host, which offers read_image and open_texture) with calls spelled as in the math.
#pragma once

#include "texgen/fade_map/test_material.h"

#include "host/host.h"
#include "texgen/fade/fade_map.h"
#include "texgen/fade/fade_stack.h"

#include <patina/abi.h>
#include <patina/testing/bsdf_checks.h>
#include <patina/shading/vec.h>

#include <dlfcn.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace patina::test {

using shading::Vec2;
using shading::Vec3;

inline const PatinaShaderDesc& spectral_km_shader()
{
    static const PatinaShaderDesc* desc = [] {
        const std::string path = std::string(PATINA_TEST_PLUGIN_DIR) + "/patina_spectral_km.so";
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle)
            throw std::runtime_error(std::string("dlopen failed: ") + dlerror());
        auto entry =
            reinterpret_cast<PatinaPluginEntryFn>(dlsym(handle, PATINA_PLUGIN_ENTRY_SYMBOL));
        if (!entry)
            throw std::runtime_error("no entry point in " + path);
        const PatinaPluginInfo* info = entry(default_host().c_host());
        for (int i = 0; info && i < info->shader_count; ++i)
            if (std::strcmp(info->shaders[i].name, "spectral_km") == 0)
                return &info->shaders[i];
        throw std::runtime_error("no spectral_km shader in " + path);
    }();
    return *desc;
}

/// A fade stack of the test material in which every texel has received `dose` J/m².
inline std::filesystem::path write_uniform_stack(const std::string& name, double dose,
                                                 double max_dose = 1e7, int entries = 24)
{
    namespace fs = std::filesystem;
    using namespace texgen::fade;
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "spectral_km" / name;
    fs::remove_all(dir);
    DoseTableOptions o;
    o.max_dose_j_m2 = max_dose;
    o.knee_dose_j_m2 = max_dose * 1e-3;
    o.entries = entries;
    o.sublayers = 40;
    const DoseTable table = DoseTable::build(fading_test_material(), illuminant_by_name("D65"),
                                             fading_test_grid(), o);
    FadeStackInfo info;
    info.material = "test_magenta_layer";
    info.illuminant = "D65";
    info.substrate = fading_test_grid().sample(fading_test_material().substrate_reflectance);
    info.width = 8;
    info.height = 8;
    std::vector<float> pixels;
    for (int i = 0; i < 64; ++i) {
        pixels.push_back(static_cast<float>(table_coordinate(table, dose)));
        pixels.push_back(static_cast<float>(dose));
        pixels.push_back(1.0f);  // coverage
    }
    write_fade_stack(dir, table, info, pixels);
    return dir / kFadeToml;
}

/// The parameters of one instance (declaration order: fade, coat, coat_roughness,
/// coat_ior, substrate).
struct KmParams {
    std::string fade;
    float coat = 0.0f;
    float coat_roughness = 0.1f;
    float coat_ior = 1.5f;
    std::vector<float> substrate_nm{550.0f};
    std::vector<float> substrate{-1.0f};
};

/// One instance; empty (with the host's error in `error`) when create refused it.
class KmBsdf {
public:
    explicit KmBsdf(const KmParams& p) : desc_(&spectral_km_shader()), params_(p)
    {
        PatinaParamValue v[5] = {};
        v[0].type = PATINA_PARAM_FILE;
        v[0].s = params_.fade.c_str();
        v[1].type = v[2].type = v[3].type = PATINA_PARAM_FLOAT;
        v[1].f = p.coat;
        v[2].f = p.coat_roughness;
        v[3].f = p.coat_ior;
        v[4].type = PATINA_PARAM_SPECTRUM;
        v[4].spectrum = {static_cast<int>(params_.substrate.size()),
                         params_.substrate_nm.data(), params_.substrate.data()};
        const Host* host = Host::from_c(default_host().c_host());
        host->take_errors();
        instance_ = desc_->create(default_host().c_host(), v);
        for (const std::string& e : host->take_errors())
            error += e + "\n";
        ctx_.N = {0.0f, 0.0f, 1.0f};
        ctx_.Ng = ctx_.N;
        ctx_.dPdu = {1.0f, 0.0f, 0.0f};
        ctx_.dPdv = {0.0f, 1.0f, 0.0f};
        ctx_.uv = {0.3f, 0.6f};
        set_wavelengths({400.0f, 450.0f, 500.0f, 530.0f, 560.0f, 600.0f, 650.0f, 700.0f});
    }
    ~KmBsdf()
    {
        if (instance_)
            desc_->destroy(instance_);
    }
    KmBsdf(const KmBsdf&) = delete;
    KmBsdf& operator=(const KmBsdf&) = delete;

    explicit operator bool() const { return instance_ != nullptr; }
    /// The instance as patina/testing/bsdf_checks.h calls it.
    BsdfCalls calls() const
    {
        BsdfCalls c(desc_->bsdf, instance_, wl_);
        c.ctx = ctx_;
        return c;
    }
    void set_wavelengths(const std::vector<float>& nm)
    {
        wl_.count = static_cast<int>(nm.size());
        for (size_t i = 0; i < nm.size() && i < PATINA_MAX_WAVELENGTHS; ++i)
            wl_.lambda_nm[i] = nm[i];
    }
    const PatinaWavelengths& wl() const { return wl_; }

    std::array<float, PATINA_MAX_WAVELENGTHS> f(Vec3 wo, Vec3 wi) const
    {
        std::array<float, PATINA_MAX_WAVELENGTHS> out{};
        desc_->bsdf->eval(instance_, &ctx_, wo, wi, &wl_, out.data());
        return out;
    }
    float pdf(Vec3 wo, Vec3 wi) const { return desc_->bsdf->pdf(instance_, &ctx_, wo, wi, &wl_); }
    bool sample(Vec3 wo, float u_lobe, Vec2 u, PatinaBsdfSample* out) const
    {
        *out = PatinaBsdfSample{};
        return desc_->bsdf->sample(instance_, &ctx_, wo, u_lobe, u, &wl_, out) != 0;
    }
    std::array<float, PATINA_MAX_WAVELENGTHS> albedo(Vec3 wo) const
    {
        std::array<float, PATINA_MAX_WAVELENGTHS> out{};
        desc_->bsdf->albedo(instance_, &ctx_, wo, &wl_, out.data());
        return out;
    }

    std::string error;

private:
    const PatinaShaderDesc* desc_;
    KmParams params_;
    void* instance_ = nullptr;
    PatinaShadingContext ctx_{};
    PatinaWavelengths wl_{};
};

}  // namespace patina::test
