// The wavefront form of the path tracer (trace_path): a batch of paths advanced one bounce
// at a time, each stage over every live path before the next (all closest-hit rays in one
// Embree stream call, then all shading, then all shadow rays in one stream call). The
// stages run back to back over many independent paths, so their memory reads overlap and
// the code and branch predictors stay warm; each path still draws its numbers and does its
// arithmetic in exactly trace_path's order, so its radiance is bitwise trace_path's.
#pragma once

#include "render/integrator.h"
#include "render/path_common.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace patina::render {

/// One path of a wavefront: the caller fills the inputs (as for trace_path with a first
/// hit); trace_wavefront fills L (and aov when asked).
struct WavefrontPath {
    // Inputs.
    Pcg32 rng;
    Ray ray;
    std::optional<Hit> hit;  ///< the camera ray's closest hit (later hits stay in the scratch)
    PatinaWavelengths wl;
    SampledSpectrum pdf;     ///< wavelength pdf; secondaries zeroed on dispersion
    CieAtWavelengths cie;
    // Output.
    SampledSpectrum L;
    PathAovs aov;
    // The path's own state between stages.
    SampledSpectrum beta;
    SampledSpectrum nee_beta, nee_value;  ///< this vertex's light sample, until its shadow ray
    int nee_bounces = 0;                  ///< the scatterings of that light (clamp_indirect)
    path::UniformSky sky;
    path::PrevVertex prev;
    int depth = 0;
    float eta_scale = 1.0f;  // η'² over the boundaries crossed: survive_roulette
    bool secondaries_terminated = false;
};

/// Scenes the wavefront handles: surfaces only (media keep the per-path loop, whose free
/// flights and transmittance queries do not split into these stages).
inline bool wavefront_supported(const Scene& scene) { return !scene.has_media; }

/// Index lists and ray buffers reused from batch to batch.
struct WavefrontScratch {
    std::vector<uint32_t> live, next, shadow_owner;
    std::vector<RayQuery> queries;
    std::vector<std::optional<Hit>> hits;
    std::vector<ShadowRay> shadows;
    std::vector<uint8_t> visible;
};

/// Trace every path of `paths` to its end: paths[i].L equals what trace_path(scene,
/// paths[i].ray, paths[i].hit, wl, cie, pdf, rng[, &aov]) returns, bit for bit, and rng and
/// pdf end as trace_path leaves them. The scene must be wavefront_supported.
void trace_wavefront(const Scene& scene, std::span<WavefrontPath> paths, bool want_aovs,
                     WavefrontScratch& scratch);

}  // namespace patina::render
