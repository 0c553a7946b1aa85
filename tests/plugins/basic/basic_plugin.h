// Test helpers: load the built patina_basic.so once (dlopen, RTLD_NOW | RTLD_LOCAL), find a
// shader by name, build parameter values from its declarations' defaults with overrides,
// and wrap instances so tests read like the math.
#pragma once

#include "test_host.h"

#include <patina/shading/frame.h>
#include <patina/testing/bsdf_checks.h>
#include <patina/shading/vec.h>

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <array>
#include <cstring>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

namespace patina::test {

using shading::Vec2;
using shading::Vec3;

/// The host every test shares (the plugin keeps its pointer while loaded).
inline TestHost& test_host()
{
    static TestHost host;
    return host;
}

struct LoadedPlugin {
    void* handle = nullptr;
    const int* abi_version = nullptr;
    const PatinaPluginInfo* info = nullptr;
    std::string error;
};

/// The basic plugin, loaded on first use and kept for the whole test run.
inline const LoadedPlugin& basic_plugin()
{
    static const LoadedPlugin plugin = [] {
        LoadedPlugin p;
        const std::string path = std::string(PATINA_TEST_PLUGIN_DIR) + "/patina_basic.so";
        p.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!p.handle) {
            p.error = std::string("dlopen failed: ") + dlerror();
            return p;
        }
        p.abi_version = static_cast<const int*>(dlsym(p.handle, PATINA_PLUGIN_VERSION_SYMBOL));
        auto entry =
            reinterpret_cast<PatinaPluginEntryFn>(dlsym(p.handle, PATINA_PLUGIN_ENTRY_SYMBOL));
        if (!p.abi_version || !entry) {
            p.error = "missing ABI symbol in " + path;
            return p;
        }
        p.info = entry(&test_host());
        if (!p.info)
            p.error = "patina_plugin_entry returned NULL";
        return p;
    }();
    return plugin;
}

/// The descriptor of a shader of the basic plugin; throws when it is missing.
inline const PatinaShaderDesc& shader(const char* name)
{
    const LoadedPlugin& p = basic_plugin();
    if (!p.info)
        throw std::runtime_error("basic plugin not loaded: " + p.error);
    for (int i = 0; i < p.info->shader_count; ++i)
        if (std::strcmp(p.info->shaders[i].name, name) == 0)
            return p.info->shaders[i];
    throw std::runtime_error(std::string("no shader named ") + name);
}

/// One value per declared parameter, defaults filled in as the host does, then overrides.
class ParamSet {
public:
    explicit ParamSet(const PatinaShaderDesc& desc) : desc_(&desc), values_(desc.param_count)
    {
        for (int i = 0; i < desc.param_count; ++i) {
            const PatinaParamDecl& d = desc.params[i];
            PatinaParamValue& v = values_[i];
            v = PatinaParamValue{};
            v.type = d.type;
            switch (d.type) {
            case PATINA_PARAM_FLOAT:
                v.f = d.default_value[0];
                break;
            case PATINA_PARAM_INT:
            case PATINA_PARAM_BOOL:
                v.i = static_cast<int>(d.default_value[0]);
                v.f = static_cast<float>(v.i);
                break;
            case PATINA_PARAM_COLOR:
                set_color_at(i, d.default_value[0], d.default_value[1], d.default_value[2]);
                break;
            case PATINA_PARAM_SPECTRUM:
                if (d.default_spectrum)
                    v.spectrum = *d.default_spectrum;
                else
                    set_spectrum_at(i, {0.0f}, {d.default_value[0]});
                break;
            case PATINA_PARAM_STRING:
            case PATINA_PARAM_TEXTURE:
            case PATINA_PARAM_FILE:
                v.s = d.default_string ? d.default_string : "";
                break;
            }
        }
    }
    ParamSet(const ParamSet&) = delete;
    ParamSet& operator=(const ParamSet&) = delete;

    ParamSet& set_float(const char* name, float value)
    {
        PatinaParamValue& v = values_[index(name)];
        v.f = value;
        return *this;
    }
    ParamSet& set_bool(const char* name, bool value)
    {
        PatinaParamValue& v = values_[index(name)];
        v.i = value ? 1 : 0;
        v.f = value ? 1.0f : 0.0f;
        return *this;
    }
    /// Uplifts through the host as a reflectance when the declared max is <= 1, else as an
    /// emission colour (abi.h, PATINA_PARAM_COLOR).
    ParamSet& set_color(const char* name, float r, float g, float b)
    {
        set_color_at(index(name), r, g, b);
        return *this;
    }
    /// Sets the colour's uplifted spectrum directly (to test what create does with it).
    ParamSet& set_color_spectrum(const char* name, const PatinaRgbSpectrum& s)
    {
        values_[index(name)].color = s;
        return *this;
    }
    ParamSet& set_spectrum(const char* name, std::vector<float> lambda_nm, std::vector<float> value)
    {
        set_spectrum_at(index(name), std::move(lambda_nm), std::move(value));
        return *this;
    }
    /// A constant spectrum, as the host passes a single number: a 1-entry table.
    ParamSet& set_constant(const char* name, float value)
    {
        return set_spectrum(name, {550.0f}, {value});
    }

    const PatinaParamValue* data() const { return values_.data(); }

private:
    int index(const char* name) const
    {
        for (int i = 0; i < desc_->param_count; ++i)
            if (std::strcmp(desc_->params[i].name, name) == 0)
                return i;
        throw std::runtime_error(std::string("no parameter named ") + name);
    }
    void set_color_at(int i, float r, float g, float b)
    {
        PatinaParamValue& v = values_[i];
        v.rgb[0] = r;
        v.rgb[1] = g;
        v.rgb[2] = b;
        const int illuminant = desc_->params[i].max_value > 1.0f ? 1 : 0;
        test_host().rgb_to_spectrum(&test_host(), v.rgb, illuminant, &v.color);
    }
    void set_spectrum_at(int i, std::vector<float> lambda_nm, std::vector<float> value)
    {
        storage_.push_back(std::move(lambda_nm));
        const float* l = storage_.back().data();
        storage_.push_back(std::move(value));
        const std::vector<float>& val = storage_.back();
        values_[i].spectrum = {static_cast<int>(val.size()), l, val.data()};
    }

    const PatinaShaderDesc* desc_;
    std::vector<PatinaParamValue> values_;
    std::deque<std::vector<float>> storage_; // deque: elements never move
};

/// Owns one instance; empty when create refused the values.
class Instance {
public:
    Instance(const PatinaShaderDesc& desc, const ParamSet& params) : desc_(&desc)
    {
        test_host().errors.clear();
        instance_ = desc.create(&test_host(), params.data());
    }
    ~Instance()
    {
        if (instance_)
            desc_->destroy(instance_);
    }
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;

    explicit operator bool() const { return instance_ != nullptr; }
    const void* get() const { return instance_; }
    const PatinaShaderDesc& desc() const { return *desc_; }

private:
    const PatinaShaderDesc* desc_;
    void* instance_ = nullptr;
};

/// `count` wavelengths spread over 360-830 nm (or the given ones).
inline PatinaWavelengths wavelengths(std::vector<float> lambda = {400.0f, 480.0f, 560.0f, 640.0f,
                                                                  720.0f, 800.0f, 380.0f, 600.0f})
{
    PatinaWavelengths wl{};
    wl.count = static_cast<int>(std::min<size_t>(lambda.size(), PATINA_MAX_WAVELENGTHS));
    for (int i = 0; i < wl.count; ++i)
        wl.lambda_nm[i] = lambda[i];
    return wl;
}

/// A BSDF instance with the calls spelled as in the math: f(wo, wi), pdf(wo, wi), sample.
class Bsdf {
public:
    Bsdf(const char* name, const ParamSet& params,
         PatinaTransportMode mode = PATINA_TRANSPORT_RADIANCE)
        : instance_(shader(name), params), funcs_(shader(name).bsdf)
    {
        ctx_ = PatinaShadingContext{};
        ctx_.N = {0.0f, 0.0f, 1.0f};
        ctx_.Ng = {0.0f, 0.0f, 1.0f};
        ctx_.dPdu = {1.0f, 0.0f, 0.0f};
        ctx_.dPdv = {0.0f, 1.0f, 0.0f};
        ctx_.mode = mode;
        wl_ = wavelengths();
    }

    explicit operator bool() const { return static_cast<bool>(instance_); }
    /// The instance as patina/testing/bsdf_checks.h calls it.
    BsdfCalls calls() const
    {
        BsdfCalls c(funcs_, instance_.get(), wl_);
        c.ctx = ctx_;
        return c;
    }
    void set_mode(PatinaTransportMode mode) { ctx_.mode = mode; }
    void set_wavelengths(const PatinaWavelengths& wl) { wl_ = wl; }
    const PatinaWavelengths& wl() const { return wl_; }

    std::array<float, PATINA_MAX_WAVELENGTHS> f(Vec3 wo, Vec3 wi) const
    {
        std::array<float, PATINA_MAX_WAVELENGTHS> out{};
        funcs_->eval(instance_.get(), &ctx_, wo, wi, &wl_, out.data());
        return out;
    }
    float f0(Vec3 wo, Vec3 wi) const { return f(wo, wi)[0]; }
    float pdf(Vec3 wo, Vec3 wi) const { return funcs_->pdf(instance_.get(), &ctx_, wo, wi, &wl_); }
    bool sample(Vec3 wo, float u_lobe, Vec2 u, PatinaBsdfSample* out) const
    {
        *out = PatinaBsdfSample{};
        return funcs_->sample(instance_.get(), &ctx_, wo, u_lobe, u, &wl_, out) != 0;
    }
    std::array<float, PATINA_MAX_WAVELENGTHS> albedo(Vec3 wo) const
    {
        std::array<float, PATINA_MAX_WAVELENGTHS> out{};
        if (funcs_->albedo)
            funcs_->albedo(instance_.get(), &ctx_, wo, &wl_, out.data());
        return out;
    }

private:
    Instance instance_;
    const PatinaBsdfFuncs* funcs_;
    PatinaShadingContext ctx_{};
    PatinaWavelengths wl_{};
};

/// A medium instance with the calls spelled as in the math: Tr(t), sample_distance, p(wo, wi)
/// and phase sampling. Positions and directions are world space; a homogeneous medium
/// ignores them, so they default to a ray from the origin along +z.
class Medium {
public:
    using Spectrum = std::array<float, PATINA_MAX_WAVELENGTHS>;

    /// What sample_distance returned.
    struct Distance {
        bool scattered = false;
        float t = 0.0f;
        Spectrum weight{};
    };

    Medium(const char* name, const ParamSet& params)
        : instance_(shader(name), params), funcs_(shader(name).medium)
    {
        wl_ = wavelengths();
    }

    explicit operator bool() const { return static_cast<bool>(instance_); }
    void set_wavelengths(const PatinaWavelengths& wl) { wl_ = wl; }
    const PatinaWavelengths& wl() const { return wl_; }

    Spectrum transmittance(float t, float u = 0.5f) const
    {
        Spectrum tr{};
        funcs_->transmittance(instance_.get(), &ctx_, origin_, dir_, t, u, &wl_, tr.data());
        return tr;
    }
    Distance sample_distance(float t_max, float u) const
    {
        Distance d;
        d.t = -1.0f;
        d.scattered = funcs_->sample_distance(instance_.get(), &ctx_, origin_, dir_, t_max, u, &wl_,
                                              &d.t, d.weight.data()) != 0;
        return d;
    }
    /// p(wo, wi) per wavelength; *pdf receives the returned pdf when not null.
    Spectrum phase(Vec3 wo, Vec3 wi, float* pdf = nullptr) const
    {
        Spectrum p{};
        const float q = funcs_->phase_eval(instance_.get(), &ctx_, wo, wi, &wl_, p.data());
        if (pdf)
            *pdf = q;
        return p;
    }
    float phase0(Vec3 wo, Vec3 wi) const { return phase(wo, wi)[0]; }
    /// Samples wi; returns the pdf (0 on failure) and fills p(wo, wi).
    float phase_sample(Vec3 wo, Vec2 u, Vec3* wi, Spectrum* p) const
    {
        PatinaVec3 w{};
        *p = Spectrum{};
        const float pdf = funcs_->phase_sample(instance_.get(), &ctx_, wo, u, &wl_, &w, p->data());
        *wi = w;
        return pdf;
    }

private:
    Instance instance_;
    const PatinaMediumFuncs* funcs_;
    PatinaShadingContext ctx_{};
    PatinaWavelengths wl_{};
    PatinaVec3 origin_{0.0f, 0.0f, 0.0f};
    PatinaVec3 dir_{0.0f, 0.0f, 1.0f};
};

/// Unit direction from spherical coordinates in the local frame.
inline Vec3 direction(float theta, float phi)
{
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

/// Small deterministic generator (PCG32, O'Neill 2014) for reproducible tests.
class Pcg32 {
public:
    explicit Pcg32(uint64_t seed = 0x853c49e6748fea9bULL, uint64_t stream = 0xda3e39cb94b95bdbULL)
    {
        inc_ = (stream << 1u) | 1u;
        next_u32();
        state_ += seed;
        next_u32();
    }
    uint32_t next_u32()
    {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ULL + inc_;
        const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
    }
    /// Uniform in [0, 1).
    float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
    Vec2 next_vec2()
    {
        const float a = next_float();
        return {a, next_float()};
    }

private:
    uint64_t state_ = 0;
    uint64_t inc_ = 0;
};

/// Directional albedo ∫ f(wo, wi) |cos θi| dωi at the first wavelength by quadrature over
/// the sphere (patina/testing/bsdf_checks.h; the grid's pole along `pole`).
inline double albedo_by_quadrature(const Bsdf& bsdf, Vec3 wo, int theta_res = 512,
                                   Vec3 pole = Vec3(0.0f, 1.0f, 0.0f))
{
    return albedo_by_quadrature(bsdf.calls(), wo, theta_res, pole)[0];
}

/// Directional albedo at the first wavelength by the BSDF's own importance sampling, over
/// about `count` stratified samples (patina/testing/bsdf_checks.h).
inline double albedo_by_sampling(const Bsdf& bsdf, Vec3 wo, int count)
{
    const int n = std::max(1, static_cast<int>(std::lround(std::sqrt(count))));
    return albedo_by_sampling(bsdf.calls(), wo, n)[0];
}

} // namespace patina::test
