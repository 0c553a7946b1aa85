// `patina-texgen flatten`: a patina stack (thickness maps + materials) turned into the
// per-texel parameters of ordinary BRDFs (flat_texel.h), as maps other renderers read.
#pragma once

#include "core/color_management.h"
#include "texgen/flatten/gltf_albedo.h"
#include "texgen/flatten/patina_stack_files.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen {

struct FlattenOptions {
    /// Encoding of the colour maps: "srgb" (sRGB-encoded Rec.709, OCIO "srgb_texture") or
    /// "acescg" (linear ACEScg, OCIO "ACEScg").
    std::string color_space = "srgb";
    int resolution = 0;          ///< texels per tile side of the output; 0: the stack's
    bool half = false;           ///< half-float EXRs
    double texel_size_m = 0.0;   ///< world size of a texel; 0: from a strip's strip_size_m
    double normal_scale = 1.0;   ///< height exaggeration of the normal map (1: true relief)
    /// The renderer the glTF maps are fitted for (gltf_fit.h): their base colour makes that
    /// renderer's glTF BRDF reflect what layered_km's does at every angle.
    GltfTarget target = GltfTarget::khronos;
    /// The maps to fill (by name; "normal" fills "height" too, which it is made from);
    /// empty: all. The others are listed with no texels, and their memory is never touched
    /// (export needs the glTF maps, normal and height only).
    std::vector<std::string> only;
};

/// One flattened map in memory: what it holds and its values per tile (texel-major,
/// channels interleaved, row 0 at the top). Colour maps are linear Rec.709 here.
struct FlatMap {
    std::string name;
    std::vector<std::string> channels;
    std::string units;
    std::string description;
    bool is_color = false;
    std::vector<std::vector<float>> tiles;
};

struct FlattenedStack {
    int width = 0, height = 0;
    std::vector<int> udims;
    double texel_size_m = 0.0;
    std::vector<FlatMap> maps;
};

/// The OCIO colour space of a --color-space value; throws std::runtime_error for others.
std::string flatten_colorspace(const std::string& option);

/// Read the thickness maps of `stack` and flatten every texel with the optics its
/// manifest records (flat_texel.h; colours through `colors`). Throws std::runtime_error
/// naming the file for an unreadable map, a map without a "thickness" channel or of another
/// size than the others, a NaN, infinite or negative texel (with its position), and naming
/// the manifest for a material it records no optics of.
FlattenedStack flatten_stack(const PatinaStackFiles& stack, const ColorManager& colors,
                             const FlattenOptions& options);

/// Throws std::runtime_error "<command> of '<manifest>': map '<name>' texel (x, y) of tile T
/// channel 'C' is not finite; nothing was written" for the first NaN or infinite value of
/// `flat`'s maps; a map with no texels (FlattenOptions::only) is skipped.
void check_finite_maps(const FlattenedStack& flat, const std::filesystem::path& manifest,
                       const char* command);

/// Write every map of `flat` into `out_dir` as tiled, mip-mapped EXRs (colour maps
/// converted through OCIO to options.color_space, data maps raw), and record them in
/// `<out_dir>/stack.toml` (baker "flatten", with a [flatten] table), replacing an earlier
/// flatten's entries. Every file is checked before the first is written and each is
/// written under a temporary name and renamed. Returns the files written.
std::vector<std::filesystem::path> write_flattened(const std::filesystem::path& out_dir,
                                                   const FlattenedStack& flat,
                                                   const PatinaStackFiles& stack,
                                                   const FlattenOptions& options,
                                                   const ColorManager& colors);

}  // namespace patina::texgen
