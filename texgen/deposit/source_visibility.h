// How much of a deposit source a surface point sees: for an area source (sphere, disc,
// rectangle) the form factor from the point to the source with shadow rays through the scene,
//
//     F = (1/pi) * integral over the source's solid angle of V(w) max(0, N.w) dw,
//
// the cos-weighted fraction of the hemisphere the visible source fills (for an unoccluded
// sphere of radius R at distance d straight above, F = (R/d)^2: the cone of half-angle
// asin(R/d) projects onto a disc of radius R/d of the unit disc, Nusselt's analogue). A point
// inside a sphere source sees it all: F = 1. Disc and rectangle deposit on both sides.
// For a directional source, the normalised catch of directional_catch (1 for an open surface
// facing it). Shadow rays of area sources end at the source; those of directional sources
// reach `max_distance`.
#pragma once

#include "core/embree_scene.h"
#include "core/sampling.h"
#include "texgen/deposit/deposit_sources.h"
#include "texgen/texels/surface_samples.h"

namespace patina::texgen {

/// The visibility of `source` from `s` (without its strength), estimated with `rays` shadow
/// rays (at least 1) stratified on a jittered grid.
float source_visibility(const EmbreeScene& scene, const SurfaceSample& s,
                        const DepositSource& source, int rays, float max_distance, Pcg32& rng);

} // namespace patina::texgen
