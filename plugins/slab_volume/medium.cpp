/*
 * slab_volume — Weathered stone as a heterogeneous participating medium (medium)
 * ==============================================================================
 *
 *  Parameter        Type   Default             Description
 *  ---------------  -----  ------------------  ---------------------------------------------
 *  file             file   (required)          World-grid stone volume (patina-texgen stone).
 *  sigma_t          float  200                 Extinction of solid stone (density 1), 1/m.
 *  stone_albedo     color  [0.93, 0.90, 0.84]  Single-scattering albedo of fresh stone.
 *  crust_albedo     color  [0.06, 0.05, 0.05]  ... of black crust.
 *  iron_albedo      color  [0.80, 0.55, 0.25]  ... of iron oxide (yellowing).
 *  salt_albedo      color  [0.97, 0.97, 0.96]  ... of salt efflorescence.
 *  forward_k        float  0.6                 Schlick k of the forward lobe, [0, 0.99].
 *  backward_k       float  -0.3                Schlick k of the backward lobe, [-0.99, 0].
 *  forward_weight   float  0.8                 Weight of the forward lobe, [0, 1].
 *  crust_gain       float  1                   Crust fraction that counts as full cover: ×.
 *  iron_gain        float  1                   The same for iron oxide.
 *  salt_gain        float  1                   The same for salt.
 *
 * Dorsey et al. 1999 §5 treat stone as a participating medium: light refracted into it is
 * scattered by grains, bubbles and micro-cracks. This medium reads the voxels the stone
 * simulation writes (density, crust, iron, salt; see volume_file.h for the format) and
 * interpolates them trilinearly at world position x (§4.1). The volume is in world
 * coordinates: place the stone's mesh without a transform (or with the one the volume was
 * made with).
 *
 *   extinction   σt(x) = sigma_t · density(x)                     (grey: every wavelength)
 *   albedo       a(x, λ) = (1 − c − i − s) a_stone + c a_crust + i a_iron + s a_salt,
 *                c, i, s the crust, iron and salt fractions at x times their gains, each
 *                clamped to [0, 1] (scaled down to sum 1 when they sum above it);
 *                σs = a σt, σa = (1 − a) σt. A gain > 1 says how strongly a small
 *                concentration colours the stone (a simulation's fractions are
 *                concentrations, not coverage).
 *   phase        p = w p_k1 + (1 − w) p_k2, two Schlick lobes (§5.1; patina/volume/
 *                schlick_phase.h), sampled exactly; its pdf is p
 *
 * The albedo colours are COLOR parameters in the scene's colour space: the host converts
 * them to the working space and uplifts them to smooth spectra. They are *single-scattering*
 * albedos: after many scattering events the stone looks darker and more saturated than
 * these colours (isotropic scatterers of albedo a reflect (1 − √(1−a)) / (1 + √(1−a)): 0.52
 * for a = 0.9: the hemispherical reflectance of Hapke 1981, J. Geophys. Res. 86).
 *
 * sample_distance is delta tracking (§5.1 "the probability of a ray interacting with the
 * medium", Eq. 3, sampled without bias instead of by ray marching) against a coarse majorant
 * grid of 4³-voxel blocks: a real collision scatters with weight a(x, λ) per wavelength,
 * and a ray that passes has weight 1. transmittance is ratio tracking against the same
 * majorants (Eq. 2, unbiased). Both draw their random numbers from a generator seeded by u
 * and the ray (patina/volume/tracking.h), so results are deterministic.
 *
 * References: J. Dorsey, A. Edelman, H. W. Jensen, J. Legakis, H. K. Pedersen 1999,
 * "Modeling and Rendering of Weathered Stone", SIGGRAPH, §5; P. Blasi, B. Le Saëc,
 * C. Schlick 1993, "A Rendering Algorithm for Discrete Volume Density Objects",
 * Eurographics; E. Woodcock et al. 1965 (delta tracking); J. Novák, A. Selle, W. Jarosz
 * 2014, "Residual Ratio Tracking", SIGGRAPH Asia (ratio tracking); pbrt-v4 §11.4, §14.2.
 */
#include "slab_volume.h"
#include "volume_file.h"

#include <patina/shading/spectral.h>
#include <patina/volume/majorant_grid.h>
#include <patina/volume/medium_phase.h>
#include <patina/volume/schlick_phase.h>
#include <patina/volume/stone_albedo.h>
#include <patina/volume/tracking.h>

#include <cmath>

namespace patina::slab_volume {
namespace {

    using namespace patina::shading;
    using volume::unit_direction;
    using volume::VoxelGrid;

    constexpr const char* kName = "slab_volume";
    /// Voxels per majorant block edge: small enough to follow the stone's surface, large
    /// enough that the walk costs little next to the density lookups.
    constexpr int kMajorantBlock = 4;

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"file", PATINA_PARAM_FILE, {0.0f, 0.0f, 0.0f}, "", nullptr, 0.0f, 0.0f, "",
         "World-grid stone volume written by patina-texgen stone (two-part EXR: voxels with "
         "density, crust, iron, salt; bounds)."},
        {"sigma_t", PATINA_PARAM_FLOAT, {200.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e6f, "1/m",
         "Extinction coefficient of solid stone; the medium's is sigma_t * density."},
        {"stone_albedo", PATINA_PARAM_COLOR, {0.93f, 0.90f, 0.84f}, nullptr, nullptr, 0.0f, 1.0f,
         "scene_linear", "Single-scattering albedo of fresh stone."},
        {"crust_albedo", PATINA_PARAM_COLOR, {0.06f, 0.05f, 0.05f}, nullptr, nullptr, 0.0f, 1.0f,
         "scene_linear", "Single-scattering albedo of black crust."},
        {"iron_albedo", PATINA_PARAM_COLOR, {0.80f, 0.55f, 0.25f}, nullptr, nullptr, 0.0f, 1.0f,
         "scene_linear", "Single-scattering albedo of iron oxide (yellowing)."},
        {"salt_albedo", PATINA_PARAM_COLOR, {0.97f, 0.97f, 0.96f}, nullptr, nullptr, 0.0f, 1.0f,
         "scene_linear", "Single-scattering albedo of salt efflorescence."},
        {"forward_k", PATINA_PARAM_FLOAT, {0.6f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 0.99f, "",
         "Schlick parameter k of the forward-scattering lobe (0 is isotropic)."},
        {"backward_k", PATINA_PARAM_FLOAT, {-0.3f, 0.0f, 0.0f}, nullptr, nullptr, -0.99f, 0.0f, "",
         "Schlick parameter k of the backward-scattering lobe (0 is isotropic)."},
        {"forward_weight", PATINA_PARAM_FLOAT, {0.8f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1.0f, "",
         "Weight of the forward lobe; the backward lobe has 1 - forward_weight."},
        {"crust_gain", PATINA_PARAM_FLOAT, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e4f, "",
         "Multiplies the voxels' crust fraction before mixing (clamped to 1): how strongly a "
         "small concentration darkens the stone."},
        {"iron_gain", PATINA_PARAM_FLOAT, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e4f, "",
         "Multiplies the voxels' iron oxide fraction before mixing (clamped to 1)."},
        {"salt_gain", PATINA_PARAM_FLOAT, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e4f, "",
         "Multiplies the voxels' salt fraction before mixing (clamped to 1)."},
    };
    // clang-format on

    /// The albedo of stone, crust, iron and salt, and the gains of the last three.
    constexpr const char* kAlbedoNames[4] = {"stone_albedo", "crust_albedo", "iron_albedo",
                                             "salt_albedo"};
    constexpr const char* kGainNames[volume::kCompositionCount] = {"crust_gain", "iron_gain",
                                                                   "salt_gain"};

    struct SlabVolume {
        VoxelGrid grid;
        volume::MajorantGrid majorants;
        float sigma_t = 0.0f;
        PatinaRgbSpectrum albedo[4] = {}; // stone, crust, iron, salt
        volume::TwoLobeSchlick phase;
        float gain[volume::kCompositionCount] = {1.0f, 1.0f, 1.0f}; // crust, iron, salt
    };

    bool in_range(const PatinaParamValue& v, float lo, float hi)
    {
        return v.type == PATINA_PARAM_FLOAT && v.f >= lo && v.f <= hi;
    }

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const PatinaParamValue& file = p.value("file", PATINA_PARAM_FILE);
        const PatinaParamValue& sigma_t = p.value("sigma_t", PATINA_PARAM_FLOAT);
        if (!in_range(sigma_t, 0.0f, 1e6f)) {
            report_error(host, kName, "sigma_t %g must lie in [0, 1e6] 1/m", sigma_t.f);
            return nullptr;
        }
        for (int c = 0; c < 4; ++c) {
            const PatinaParamValue& a = p.value(kAlbedoNames[c], PATINA_PARAM_COLOR);
            float lo = 0.0f, hi = 0.0f;
            rgb_spectrum_range(a.color, &lo, &hi);
            if (a.type != PATINA_PARAM_COLOR || !(lo >= 0.0f && hi <= 1.0f + 1e-5f)) {
                report_error(host, kName, "%s must be a reflectance colour in [0, 1]",
                             kAlbedoNames[c]);
                return nullptr;
            }
        }
        const PatinaParamValue& forward_k = p.value("forward_k", PATINA_PARAM_FLOAT);
        const PatinaParamValue& backward_k = p.value("backward_k", PATINA_PARAM_FLOAT);
        const PatinaParamValue& forward_weight = p.value("forward_weight", PATINA_PARAM_FLOAT);
        if (!in_range(forward_k, 0.0f, 0.99f) || !in_range(backward_k, -0.99f, 0.0f) ||
            !in_range(forward_weight, 0.0f, 1.0f)) {
            report_error(host, kName,
                         "forward_k %g must lie in [0, 0.99], backward_k %g in [-0.99, 0], "
                         "forward_weight %g in [0, 1]",
                         forward_k.f, backward_k.f, forward_weight.f);
            return nullptr;
        }

        for (int c = 0; c < volume::kCompositionCount; ++c)
            if (!in_range(p.value(kGainNames[c], PATINA_PARAM_FLOAT), 0.0f, 1e4f)) {
                report_error(host, kName, "%s %g must lie in [0, 1e4]", kGainNames[c],
                             p.number(kGainNames[c]));
                return nullptr;
            }

        if (!p.ok())
            return nullptr;
        auto* m = make_instance<SlabVolume>(host, kName);
        if (!m)
            return nullptr;
        if (!read_volume_file(host, kName, file.type == PATINA_PARAM_FILE ? file.s : nullptr,
                              &m->grid)) {
            delete m;
            return nullptr;
        }
        try {
            m->majorants = volume::MajorantGrid(m->grid, kMajorantBlock);
        } catch (const std::bad_alloc&) {
            report_error(host, kName, "out of memory");
            delete m;
            return nullptr;
        }
        m->sigma_t = sigma_t.f;
        for (int c = 0; c < 4; ++c)
            m->albedo[c] = p.value(kAlbedoNames[c], PATINA_PARAM_COLOR).color;
        m->phase.k_forward = forward_k.f;
        m->phase.k_backward = backward_k.f;
        m->phase.w_forward = forward_weight.f;
        for (int c = 0; c < volume::kCompositionCount; ++c)
            m->gain[c] = p.number(kGainNames[c]);
        return m;
    }

    void destroy(void* instance)
    {
        delete static_cast<SlabVolume*>(instance);
    }

    /// The single-scattering albedo at x from the voxels' composition (see the top).
    SpectralArray albedo_at(const SlabVolume& m, Vec3 x, const PatinaWavelengths& wl)
    {
        float density = 0.0f, q[volume::kCompositionCount] = {}, w[4];
        m.grid.sample(x, &density, q);
        volume::albedo_weights(q, m.gain, w);
        SpectralArray a = eval_rgb(m.albedo[0], wl) * w[0];
        a += eval_rgb(m.albedo[1], wl) * w[1];
        a += eval_rgb(m.albedo[2], wl) * w[2];
        a += eval_rgb(m.albedo[3], wl) * w[3];
        return a;
    }

    int sample_distance(const void* instance, const PatinaShadingContext*, PatinaVec3 origin,
                        PatinaVec3 dir, float t_max, float u, const PatinaWavelengths* wl,
                        float* t, float* weight)
    {
        const auto& m = *static_cast<const SlabVolume*>(instance);
        const Vec3 o(origin);
        Vec3 d;
        const double t_end = t_max > 0.0f ? static_cast<double>(t_max) : 0.0; // NaN -> 0
        fill(1.0f, *wl, weight);
        *t = static_cast<float>(t_end);
        if (!unit_direction(dir, &d) || !is_finite(o) || !(m.sigma_t > 0.0f))
            return 0;

        // Delta tracking against the block majorants: the first real collision is
        // distributed as σt(x) T(x), Eq. 3 of §5.1
        volume::TrackingRng rng(u, o, d);
        const double sigma_scale = m.sigma_t;
        auto sigma_t = [&](double s) {
            return sigma_scale * m.grid.density(o + d * static_cast<float>(s));
        };
        double t_hit = 0.0;
        if (!volume::delta_track(m.majorants, sigma_scale, o, d, t_end, sigma_t, rng, &t_hit))
            return 0;
        const float ts = static_cast<float>(t_hit);
        if (!(ts < t_max))
            return 0;
        // A real collision scatters with weight σs/σt = a(x, λ); absorption is in the weight
        store(albedo_at(m, o + d * ts, *wl), *wl, weight);
        *t = ts;
        return 1;
    }

    void transmittance(const void* instance, const PatinaShadingContext*, PatinaVec3 origin,
                       PatinaVec3 dir, float t, float u, const PatinaWavelengths* wl, float* tr)
    {
        const auto& m = *static_cast<const SlabVolume*>(instance);
        const Vec3 o(origin);
        Vec3 d;
        const double t_end = t > 0.0f ? static_cast<double>(t) : 0.0;
        if (!unit_direction(dir, &d) || !is_finite(o) || !(m.sigma_t > 0.0f) || t_end == 0.0) {
            fill(1.0f, *wl, tr);
            return;
        }
        // Ratio tracking: an unbiased estimate of Eq. 2, τ = exp(−∫ κ)
        volume::TrackingRng rng(u, o, d);
        const double sigma_scale = m.sigma_t;
        auto sigma_t = [&](double s) {
            return sigma_scale * m.grid.density(o + d * static_cast<float>(s));
        };
        const double value = volume::ratio_track(m.majorants, sigma_scale, o, d, t_end, sigma_t, rng);
        fill(static_cast<float>(value), *wl, tr);
    }

    const PatinaMediumFuncs kFuncs = {sample_distance, transmittance,
                                      volume::phase_eval<SlabVolume, &SlabVolume::phase>,
                                      volume::phase_sample<SlabVolume, &SlabVolume::phase>};

} // namespace

PatinaShaderDesc slab_volume_shader()
{
    return describe(
        kName,
        "Weathered stone (Dorsey et al. 1999 Sec. 5): extinction and albedo from the voxels of a "
        "stone simulation, two-lobe Schlick phase function, delta and ratio tracking.",
        kParams, create, destroy, kFuncs);
}

} // namespace patina::slab_volume
