/*
 * checker_lambert — a diffuse BSDF whose reflectance alternates between two colours in a
 * checkerboard over the surface's uv coordinates. A template for out-of-tree plugins: it
 * needs nothing but <patina/abi.h> and the header-only helpers beside it
 * (patina/plugin_support.h: parameters read by name, descriptors, the entry point).
 * checker_test.cpp tests it as every BSDF of Patina is tested (patina/testing/).
 *
 * Parameters:
 *   color_a  color [0,1]  reflectance of the even squares (default 0.8 grey)
 *   color_b  color [0,1]  reflectance of the odd squares (default 0.2 grey)
 *   scale    float >0     squares per unit of uv (default 8)
 */
#include <patina/plugin_support.h>

#include <cmath>

namespace {

constexpr const char* kName = "checker_lambert";
constexpr float kInvPi = 0.318309886f;

struct Checker {
    PatinaRgbSpectrum a, b;
    float scale;
};

const PatinaParamDecl kParams[] = {
    {"color_a", PATINA_PARAM_COLOR, {0.8f, 0.8f, 0.8f}, nullptr, nullptr, 0.0f, 1.0f,
     "scene_linear", "reflectance of the even squares"},
    {"color_b", PATINA_PARAM_COLOR, {0.2f, 0.2f, 0.2f}, nullptr, nullptr, 0.0f, 1.0f,
     "scene_linear", "reflectance of the odd squares"},
    {"scale", PATINA_PARAM_FLOAT, {8.0f, 0, 0}, nullptr, nullptr, 1e-3f, 1e4f, "1/uv",
     "squares per unit of uv"},
};

void* create(const PatinaHost* host, const PatinaParamValue* values)
{
    // By name: a renamed or reordered table cannot silently rebind a value.
    const patina::plugin::Parameters p(host, kName, kParams, values);
    const PatinaRgbSpectrum& a = p.value("color_a", PATINA_PARAM_COLOR).color;
    const PatinaRgbSpectrum& b = p.value("color_b", PATINA_PARAM_COLOR).color;
    const float scale = p.number("scale");
    if (!p.ok())
        return nullptr;
    return patina::plugin::make_instance<Checker>(host, kName, a, b, scale);
}

void destroy(void* p) { delete static_cast<Checker*>(p); }

const PatinaRgbSpectrum& square(const Checker& c, const PatinaShadingContext* ctx)
{
    if (!ctx)
        return c.a;
    const long i = std::lround(std::floor(ctx->uv.x * c.scale)) +
                   std::lround(std::floor(ctx->uv.y * c.scale));
    return (i & 1) ? c.b : c.a;
}

void eval(const void* inst, const PatinaShadingContext* ctx, PatinaVec3 wo, PatinaVec3 wi,
          const PatinaWavelengths* wl, float* f)
{
    const PatinaRgbSpectrum& r = square(*static_cast<const Checker*>(inst), ctx);
    const bool above = wo.z > 0 && wi.z > 0;
    for (int i = 0; i < wl->count; ++i)
        f[i] = above ? patina_rgb_spectrum_eval(&r, wl->lambda_nm[i]) * kInvPi : 0.0f;
}

float pdf(const void*, const PatinaShadingContext*, PatinaVec3 wo, PatinaVec3 wi,
          const PatinaWavelengths*)
{
    return (wo.z > 0 && wi.z > 0) ? wi.z * kInvPi : 0.0f;
}

int sample(const void* inst, const PatinaShadingContext* ctx, PatinaVec3 wo, float,
           PatinaVec2 u, const PatinaWavelengths* wl, PatinaBsdfSample* out)
{
    if (wo.z <= 0)
        return 0;
    // Cosine-weighted hemisphere (Malley's method on a uniform disk).
    const float r = std::sqrt(u.x), phi = 6.28318531f * u.y;
    const float z = std::sqrt(std::fmax(0.0f, 1.0f - u.x));
    out->wi = {r * std::cos(phi), r * std::sin(phi), z};
    if (z <= 0)
        return 0;
    eval(inst, ctx, wo, out->wi, wl, out->f);
    out->pdf = z * kInvPi;
    out->lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_DIFFUSE;
    out->eta = 1.0f;
    return 1;
}

const PatinaBsdfFuncs kBsdf = {eval, pdf, sample, nullptr};

}  // namespace

PATINA_PLUGIN("checker", "1.0",
              patina::plugin::describe(kName, "diffuse checkerboard over uv", kParams, create,
                                       destroy, kBsdf))
