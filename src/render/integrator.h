// Spectral unidirectional path tracing through the plugin ABI: BSDF sampling, emitters hit
// by paths, a uniform environment, Russian roulette, hero wavelengths. (Light sampling
// with MIS, environment maps and media arrive with the renderer issue.)
#pragma once

#include "render/camera.h"
#include "render/shading_frame.h"
#include "render/scene.h"

#include "core/sampling.h"
#include "core/spectrum.h"

namespace patina::render {

/// Radiance along `ray` at the wavelengths `wl`. `pdf` holds the wavelength sampling pdf;
/// when a lobe disperses light the secondary wavelengths are terminated by zeroing their
/// pdf (pbrt-v4's TerminateSecondary).
SampledSpectrum trace_path(const Scene& scene, Ray ray, const PatinaWavelengths& wl,
                           SampledSpectrum& pdf, Pcg32& rng);


}  // namespace patina::render
