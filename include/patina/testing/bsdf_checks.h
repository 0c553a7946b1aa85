// The checks every BSDF of Patina passes, for a plugin's own tests (in tree and out of
// tree; header-only, needs only <patina/abi.h>): the white furnace — its directional albedo
// ∫ f(wo, wi) |cos θi| dωi by quadrature (independent of its sampler) and by its own
// importance samples, which must agree and stay ≤ 1 for a passive surface — and reciprocity,
// f(wo, wi) = f(wi, wo) for a reflection (Helmholtz; Veach 1997 §5.3 for the generalised
// form with refraction). The sampler against its pdf is chi2.h beside this.
#pragma once

#include <patina/abi.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace patina::test {

using SpectrumValues = std::array<double, PATINA_MAX_WAVELENGTHS>;

/// One BSDF instance as a host calls it: its function table, the instance, a shading
/// context (by default: +z normal, dPdu = +x, radiance transport) and wavelengths.
struct BsdfCalls {
    const PatinaBsdfFuncs* funcs = nullptr;
    const void* instance = nullptr;
    PatinaShadingContext ctx{};
    PatinaWavelengths wl{};

    BsdfCalls(const PatinaBsdfFuncs* f, const void* i, const PatinaWavelengths& w)
        : funcs(f), instance(i), wl(w)
    {
        ctx.N = ctx.Ng = {0.0f, 0.0f, 1.0f};
        ctx.dPdu = {1.0f, 0.0f, 0.0f};
        ctx.dPdv = {0.0f, 1.0f, 0.0f};
        ctx.mode = PATINA_TRANSPORT_RADIANCE;
    }

    std::array<float, PATINA_MAX_WAVELENGTHS> f(PatinaVec3 wo, PatinaVec3 wi) const
    {
        std::array<float, PATINA_MAX_WAVELENGTHS> out{};
        funcs->eval(instance, &ctx, wo, wi, &wl, out.data());
        return out;
    }
    bool sample(PatinaVec3 wo, float u_lobe, PatinaVec2 u, PatinaBsdfSample* out) const
    {
        *out = PatinaBsdfSample{};
        return funcs->sample(instance, &ctx, wo, u_lobe, u, &wl, out) != 0;
    }
};

/// A unit direction from spherical angles about `pole` (θ from the pole, φ about it); the
/// frame's other axes are any orthonormal pair.
inline PatinaVec3 direction_about(PatinaVec3 pole, double theta, double phi)
{
    // Duff et al. 2017's branchless orthonormal basis.
    const double sign = std::copysign(1.0, pole.z);
    const double a = -1.0 / (sign + pole.z), b = pole.x * pole.y * a;
    const double t[3] = {1.0 + sign * pole.x * pole.x * a, sign * b, -sign * pole.x};
    const double s[3] = {b, sign + pole.y * pole.y * a, -pole.y};
    const double st = std::sin(theta), ct = std::cos(theta);
    const double x = st * std::cos(phi), y = st * std::sin(phi);
    const double w[3] = {x * t[0] + y * s[0] + ct * pole.x, x * t[1] + y * s[1] + ct * pole.y,
                         x * t[2] + y * s[2] + ct * pole.z};
    const double n = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    return {static_cast<float>(w[0] / n), static_cast<float>(w[1] / n),
            static_cast<float>(w[2] / n)};
}

/// The white furnace by quadrature: ∫ f(wo, wi) |cos θi| dωi per wavelength over the whole
/// sphere (reflection and transmission), by the midpoint rule on a θ × φ grid of
/// theta_res × 2 theta_res cells whose pole lies along `pole` (default +y: away from lobes
/// of a wo in the x-z plane, since the rule resolves a narrow lobe poorly at a pole). Delta
/// lobes are not seen (eval never returns them).
inline SpectrumValues albedo_by_quadrature(const BsdfCalls& bsdf, PatinaVec3 wo,
                                           int theta_res = 512,
                                           PatinaVec3 pole = {0.0f, 1.0f, 0.0f})
{
    const int phi_res = 2 * theta_res;
    const double pi = 3.14159265358979323846;
    const double dtheta = pi / theta_res, dphi = 2.0 * pi / phi_res;
    SpectrumValues sum{};
    for (int i = 0; i < theta_res; ++i) {
        const double theta = (i + 0.5) * dtheta;
        const double weight = std::sin(theta) * dtheta * dphi;
        for (int j = 0; j < phi_res; ++j) {
            const PatinaVec3 wi = direction_about(pole, theta, (j + 0.5) * dphi);
            const auto f = bsdf.f(wo, wi);
            for (int c = 0; c < bsdf.wl.count; ++c)
                sum[c] += static_cast<double>(f[c]) * std::abs(wi.z) * weight;
        }
    }
    return sum;
}

/// The white furnace by the BSDF's own importance sampling: the mean of f |cos θi| / pdf
/// per wavelength over n × n stratified samples (u_lobe decorrelated from u; delta lobes
/// included, failed samples counting as 0).
inline SpectrumValues albedo_by_sampling(const BsdfCalls& bsdf, PatinaVec3 wo, int n = 64)
{
    SpectrumValues sum{};
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            PatinaBsdfSample s;
            const float u_lobe = (static_cast<float>((i * 7 + j * 13) % n) + 0.5f) / n;
            const PatinaVec2 u = {(i + 0.5f) / n, (j + 0.5f) / n};
            if (!bsdf.sample(wo, u_lobe, u, &s) || !(s.pdf > 0.0f))
                continue;
            for (int c = 0; c < bsdf.wl.count; ++c)
                sum[c] += static_cast<double>(s.f[c]) * std::abs(s.wi.z) / s.pdf;
        }
    for (double& v : sum)
        v /= static_cast<double>(n) * n;
    return sum;
}

/// Reciprocity at one pair of directions: the largest difference |f(wo, wi) − f(wi, wo)|
/// over the wavelengths, relative to the larger value (absolute below `floor`).
inline double reciprocity_error(const BsdfCalls& bsdf, PatinaVec3 wo, PatinaVec3 wi,
                                double floor = 1e-6)
{
    const auto a = bsdf.f(wo, wi), b = bsdf.f(wi, wo);
    double worst = 0.0;
    for (int c = 0; c < bsdf.wl.count; ++c) {
        const double scale = std::max({std::abs(double(a[c])), std::abs(double(b[c])), floor});
        worst = std::max(worst, std::abs(double(a[c]) - double(b[c])) / scale);
    }
    return worst;
}

}  // namespace patina::test
