// Spectral unidirectional path tracing through the plugin ABI: BSDF sampling, emitters hit
// by paths, a uniform environment, Russian roulette, hero wavelengths.
#pragma once

#include "render/camera.h"
#include "render/scene.h"
#include "render/shading_frame.h"

#include "core/sampling.h"
#include "core/spectrum.h"

namespace patina::render {

/// What the camera ray's first hit tells the AOVs.
struct PathAovs {
    bool hit = false;
    SampledSpectrum albedo;  ///< BSDF albedo estimate (0 if the shader gives none)
    Imath::V3f normal{0, 0, 0};
    float depth = 0.0f;
};

/// Radiance along `ray` at the wavelengths `wl`; `cie` holds the CIE tables at wl
/// (cie_at_wavelengths(wl)). `pdf` holds the wavelength sampling pdf; when a lobe
/// disperses light the secondary wavelengths are terminated by zeroing their pdf
/// (pbrt-v4's TerminateSecondary). `aovs`, when given, receives the first hit.
SampledSpectrum trace_path(const Scene& scene, Ray ray, const PatinaWavelengths& wl,
                           const CieAtWavelengths& cie, SampledSpectrum& pdf, Pcg32& rng,
                           PathAovs* aovs = nullptr);
/// As above, with the closest hit of `ray` already found (by a batch query such as
/// EmbreeScene::intersect_coherent); the same result as the call above.
SampledSpectrum trace_path(const Scene& scene, Ray ray, const std::optional<Hit>& first_hit,
                           const PatinaWavelengths& wl, const CieAtWavelengths& cie,
                           SampledSpectrum& pdf, Pcg32& rng, PathAovs* aovs = nullptr);

}  // namespace patina::render
