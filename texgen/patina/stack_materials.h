// The spectral optics of patina materials (what a renderer needs, D&H 1996 §4.1: K and S per
// wavelength, since "in general K and S are functions of wavelength"), and their description
// in a stack.toml ([patina.materials."<name>"]) so that a stack is self-contained: the
// layered shader (plugins/layered) reads nothing else.
//
// A layer's R_inf colour is uplifted to a smooth spectrum (core/rgb_spectrum.h, Jakob &
// Hanika 2019) in the OCIO working space, K = S (1 - R_inf)^2 / (2 R_inf) per wavelength; a
// mixture sums K and S by volume fraction (Duncan's rule); a metal keeps its n and k tables,
// or, when only its colour is known, gets n and k from it by Gulbrandsen 2014.
#pragma once

#include "core/color_management.h"
#include "formats/texture_stack/texture_stack.h"
#include "texgen/patina/material_library.h"

#include <vector>

namespace patina::texgen {

/// The grid's wavelengths: 360, 370, ..., 830 nm.
std::vector<float> spectral_grid();

/// `values` tabulated at `lambda_nm` (increasing), linearly interpolated onto the grid,
/// clamped at the ends.
std::vector<float> resample_to_grid(const std::vector<float>& lambda_nm,
                                    const std::vector<float>& values);

/// A linear Rec.709 reflectance uplifted to a spectrum on the grid (via the working space).
std::vector<float> uplift_reflectance(const Imath::V3f& lin_rec709, const ColorManager& colors);

/// The spectral optics of a material: `m.spectral` when it is filled, else derived from its
/// RGB description as the library does it.
SpectralOptics resolve_spectral(const PatinaMaterial& m, const ColorManager& colors);

/// The optics a stack.toml records for a material ([patina.materials."<name>"],
/// formats/texture_stack/texture_stack.h): its spectral optics on the grid, roughness and description.
formats::MaterialOptics stack_optics(const PatinaMaterial& m, const ColorManager& colors);

}  // namespace patina::texgen
