// The optics a stack records ([patina.materials], formats/texture_stack/texture_stack.h) at
// the wavelengths flatten and the preview evaluate the stack model at, and the weights that
// turn a reflectance there into a colour: the same spectra layered_km renders with, so
// that flatten, export, the preview and the renderer compute one material.
//
// The wavelengths: kBandCount nodes from 400 nm every 20 nm, as ASTM E308's 20 nm tables.
// A reflectance known at the nodes is read as the polyline through them (constant beyond
// the end nodes), integrated against the CIE 1931 2° observer under D65 on the 1 nm grid,
// and taken to linear Rec.709 through OpenColorIO. The weights are normalised so that a
// perfect white reflector is exactly (1, 1, 1). docs/flatten.md gives the difference to a
// 5 nm integration (what layered_km's grid holds).
#pragma once

#include "core/color_management.h"
#include "formats/texture_stack/texture_stack.h"
#include "texgen/flatten/patina_stack_files.h"

#include <patina/shading/ggx_albedo.h>
#include <patina/shading/lanes.h>

#include <Imath/ImathVec.h>

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace patina::texgen {

inline constexpr int kBandCount = 16;
inline constexpr float kBandStartNm = 400.0f;
inline constexpr float kBandStepNm = 20.0f;
inline constexpr int kBandGroups = kBandCount / shading::simd::kLanes;

/// A spectrum at the band wavelengths, four to a register.
using Bands = std::array<shading::simd::V4, kBandGroups>;

/// The wavelength of band node i (nm).
inline float band_wavelength(int i)
{
    return kBandStartNm + kBandStepNm * static_cast<float>(i);
}

/// Every node of `b` set to `value`.
Bands constant_bands(float value);

/// A material of a stack at the bands, as layered_km compiles it (plugins/layered): its
/// tables interpolated linearly at the nodes.
struct BandMaterial {
    std::string name;
    bool metal = false;
    float roughness = 0.5f;  ///< perceptual (GGX alpha = r²)
    Bands absorption{}, scattering{};  ///< KM K and S per µm; 0 for a metal
    /// Normal-incidence reflectance of its top surface: the recorded specular of a layer or
    /// dielectric base, a metal's Fresnel reflectance from n and k.
    Bands specular{};
    /// What the material returns to diffuse light as the opaque base
    /// (patina/shading/layer_stack.h): R∞ of a dielectric, a metal's hemispherical
    /// reflectance.
    Bands base_reflectance{};
    /// The directional albedo of its interface's glossy lobe at the Gauss cosines of
    /// patina/shading/ggx_albedo.h, as a colour (layered_km's E(F0, μ) at each band, or for
    /// a metal its hemispherical reflectance times the F = 1 albedo): filled by
    /// tabulate_lobe_albedos, for the albedo of a texel (flat_texel.h). R, G, B in lanes 0-2.
    std::array<shading::simd::V4, shading::kGaussNodes> lobe_albedo{};
};

/// `optics` at the bands. Throws std::runtime_error naming the material for a table whose
/// length differs from its wavelengths'.
BandMaterial band_material(const formats::MaterialOptics& optics);

/// The materials of a stack at the bands: each once (a layer of the material of the layer
/// above it is that layer continued, patina/shading/layer_stack.h, known by its address),
/// the base and the layers (bottom to top) pointing into them. Moves keep the pointers.
struct BandStack {
    std::map<std::string, BandMaterial> materials;
    const BandMaterial* base = nullptr;
    std::vector<const BandMaterial*> layers;

    BandStack() = default;
    BandStack(BandStack&&) = default;
    BandStack& operator=(BandStack&&) = default;
    BandStack(const BandStack&) = delete;
    BandStack& operator=(const BandStack&) = delete;
};

/// The stack a manifest's [patina] table describes, from the optics it records. Throws
/// std::runtime_error naming `manifest` and the layer for a material it records no optics
/// of, or a table of the wrong length.
BandStack band_stack(const formats::PatinaTable& patina, const std::filesystem::path& manifest);
BandStack band_stack(const PatinaStackFiles& stack);

class BandsToRgb;

/// Fills every material's lobe_albedo (a GGX table per material: a few milliseconds each).
void tabulate_lobe_albedos(BandStack& stack, const BandsToRgb& to_rgb);

/// A reflectance at the bands as linear Rec.709 under D65 (see the top of this file).
class BandsToRgb {
public:
    explicit BandsToRgb(const ColorManager& colors);
    Imath::V3f operator()(const Bands& reflectance) const;

    /// The weight of node i in channel c (Rec.709 R, G, B), for tests.
    float weight(int channel, int node) const { return weights_[channel][node]; }

private:
    std::array<Bands, 3> rows_{};
    std::array<std::array<float, kBandCount>, 3> weights_{};
};

}  // namespace patina::texgen
