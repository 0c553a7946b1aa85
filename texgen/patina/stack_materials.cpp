#include "texgen/patina/stack_materials.h"

#include <patina/shading/kubelka_munk.h>
#include "core/rgb_spectrum.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

namespace patina::texgen {

namespace {

    /// One uplift per colour configuration and working space (its warm-start table is
    /// built lazily and shared).
    const RgbToSpectrum& uplift_for(const ColorManager& colors)
    {
        static std::mutex mutex;
        static std::map<std::string, std::unique_ptr<RgbToSpectrum>> cache;
        const std::string key = colors.config_path().string() + "|" + colors.working_space();
        std::lock_guard<std::mutex> lock(mutex);
        auto& entry = cache[key];
        if (!entry)
            entry = std::make_unique<RgbToSpectrum>(colors.working_rgb_to_xyz());
        return *entry;
    }

    /// n and k of a metal from its normal-incidence colour r, with the edge tint g = r:
    /// Gulbrandsen 2014, "Artist Friendly Metallic Fresnel", JCGT 3(4), Eqs. 3-4 (inverse).
    void metal_index(float r, float* n, float* k)
    {
        r = std::clamp(r, 1e-4f, 0.9999f);
        const float g = r;
        const float sr = std::sqrt(r);
        *n = g * (1.0f - r) / (1.0f + r) + (1.0f - g) * (1.0f + sr) / (1.0f - sr);
        *k = std::sqrt(std::max(0.0f, ((*n + 1.0f) * (*n + 1.0f) * r -
                                       (*n - 1.0f) * (*n - 1.0f)) / (1.0f - r)));
    }

}  // namespace

std::vector<float> spectral_grid()
{
    std::vector<float> g(kSpectralSamples);
    for (int i = 0; i < kSpectralSamples; ++i)
        g[i] = kSpectralStartNm + kSpectralStepNm * static_cast<float>(i);
    return g;
}

std::vector<float> resample_to_grid(const std::vector<float>& lambda_nm,
                                    const std::vector<float>& values)
{
    const PatinaTabulatedSpectrum table{static_cast<int>(values.size()), lambda_nm.data(),
                                        values.data()};
    std::vector<float> out;
    for (float l : spectral_grid())
        out.push_back(patina_tabulated_eval(&table, l));
    return out;
}

std::vector<float> uplift_reflectance(const Imath::V3f& lin_rec709, const ColorManager& colors)
{
    float rgb[3] = {lin_rec709.x, lin_rec709.y, lin_rec709.z};
    colors.convert("lin_rec709", colors.working_space(), rgb, 1);
    const PatinaRgbSpectrum s =
        uplift_for(colors).uplift({rgb[0], rgb[1], rgb[2]}, /*illuminant=*/false);
    std::vector<float> out;
    for (float l : spectral_grid())
        out.push_back(std::clamp(RgbToSpectrum::eval(s, l), 0.0f, 1.0f));
    return out;
}

SpectralOptics resolve_spectral(const PatinaMaterial& m, const ColorManager& colors)
{
    if (!m.spectral.lambda_nm.empty())
        return m.spectral;
    SpectralOptics o;
    o.lambda_nm = spectral_grid();
    o.specular = uplift_reflectance(m.specular, colors);
    if (m.is_metal) {
        const std::vector<float> r = uplift_reflectance(m.color, colors);
        for (float x : r) {
            float n, k;
            metal_index(x, &n, &k);
            o.n.push_back(n);
            o.k.push_back(k);
        }
        o.absorption.assign(kSpectralSamples, 0.0f);
        o.scattering.assign(kSpectralSamples, 0.0f);
        return o;
    }
    // A layer known by its RGB K and S: R_inf per channel is the colour (D&H 1996 §4.1), S
    // the mean of the channels' S (S is a single assumed number in the library).
    Imath::V3f r_inf;
    for (int c = 0; c < 3; ++c)
        r_inf[c] = static_cast<float>(shading::km_r_infinity(
            m.scattering[c] > 0.0f ? m.absorption[c] / m.scattering[c] : 0.0f));
    const float S = (m.scattering[0] + m.scattering[1] + m.scattering[2]) / 3.0f;
    o.r_infinity = uplift_reflectance(r_inf, colors);
    for (float& r : o.r_infinity)
        r = std::clamp(r, 1e-4f, 0.9999f);
    for (float r : o.r_infinity) {
        o.scattering.push_back(S);
        o.absorption.push_back(static_cast<float>(shading::km_k_over_s(r)) * S);
    }
    return o;
}

formats::MaterialOptics stack_optics(const PatinaMaterial& m, const ColorManager& colors)
{
    const SpectralOptics o = resolve_spectral(m, colors);
    auto doubles = [](const std::vector<float>& v) { return std::vector<double>(v.begin(), v.end()); };
    formats::MaterialOptics t;
    t.name = m.name;
    t.description = m.description;
    t.metal = m.is_metal;
    t.roughness = static_cast<double>(m.roughness);
    t.lambda_nm = doubles(o.lambda_nm);
    if (m.is_metal) {
        t.n = doubles(o.n);
        t.k = doubles(o.k);
    } else {
        t.absorption_per_um = doubles(o.absorption);
        t.scattering_per_um = doubles(o.scattering);
    }
    t.specular = doubles(o.specular);
    return t;
}

}  // namespace patina::texgen
