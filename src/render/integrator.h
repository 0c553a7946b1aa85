// Spectral unidirectional path tracing through the plugin ABI: BSDF sampling, emitters hit
// by paths, a uniform environment, Russian roulette, hero wavelengths. (Light sampling
// with MIS, environment maps and media arrive with the renderer issue.)
#pragma once

#include "render/camera.h"
#include "render/scene.h"

#include "core/sampling.h"
#include "core/spectrum.h"

namespace patina::render {

/// Radiance along `ray` at the wavelengths `wl`. `pdf` holds the wavelength sampling pdf;
/// when a lobe disperses light the secondary wavelengths are terminated by zeroing their
/// pdf (pbrt-v4's TerminateSecondary).
SampledSpectrum trace_path(const Scene& scene, Ray ray, const PatinaWavelengths& wl,
                           SampledSpectrum& pdf, Pcg32& rng);

/// The shading context of a surface point, and the local frame its BSDF works in.
struct ShadingFrame {
    PatinaShadingContext ctx{};
    Imath::V3f s, t, n;  ///< orthonormal; n = shading normal

    Imath::V3f to_local(const Imath::V3f& v) const { return {v.dot(s), v.dot(t), v.dot(n)}; }
    Imath::V3f to_world(const Imath::V3f& v) const { return v.x * s + v.y * t + v.z * n; }
};

ShadingFrame make_shading_frame(const SurfacePoint& p);

}  // namespace patina::render
