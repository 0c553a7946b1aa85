// The texture stack's manifest, stack.toml (docs/file-formats.md "Texture stack"): the maps
// of an output folder (`[maps.<name>]`) and, for a patina stack, its `[patina]` table (the
// base, the layers bottom to top, the optics of every material it uses). One reader for
// every consumer (the layered_km plugin, flatten, export) and the tables the writers
// (texgen/stack/manifest.cpp, texgen/patina/stack_writer.cpp) put into it.
#pragma once

#include <toml++/toml.h>

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace patina::formats {

/// The manifest's name inside a stack folder.
inline constexpr const char* kStackManifest = "stack.toml";

/// The channel every texel map carries after its own: the texel's covered fraction, 1 where
/// baked, the covered part of the texel at an island's border, 0 where nothing was baked
/// (there the other channels hold padding or 0). It is the alpha (`A`) of an OpenEXR layer
/// of its own, `coverage`: readers list a file's channels layer by layer, the unnamed layer
/// first, so it comes after a map's own channels and never shifts their indices (a bare
/// `A` would be listed before them, after R, G, B only).
inline constexpr const char* kCoverageChannel = "coverage.A";

/// `name` (a material's) as part of a map's name and its file's: every character but an
/// ASCII letter or digit becomes '_' ("rural patina" -> "rural_patina").
std::string name_part(std::string_view name);

/// One map, `[maps.<name>]`: a lone texel map (`file`, tile 1001), a UDIM map (`pattern`
/// with `<UDIM>` and `tiles`), or a per-vertex PLY (`domain = "vertex"`, `file`).
struct StackMap {
    std::string name;
    std::string domain = "texel";
    std::string file;                   ///< relative to the manifest; empty for a UDIM map
    std::string pattern;                ///< "<name>.<UDIM>.exr"; empty for a lone file
    std::vector<int> tiles;             ///< the UDIM tiles of `pattern`
    std::vector<std::string> channels;  ///< in the file's channel order
    std::string coverage;               ///< the coverage channel (one of `channels`), or none
    std::string units, colorspace = "raw", baker, description;
    int width = 0, height = 0;          ///< texels per tile (texel maps)
    toml::table parameters;             ///< how the map was made

    /// The UDIM tiles: `tiles`, or {1001} for a lone file.
    std::vector<int> udims() const;
    /// The file of every tile (udims() order), relative to `dir` (the manifest's folder).
    std::vector<std::filesystem::path> files(const std::filesystem::path& dir) const;
    /// The index of `channel` in `channels`, or -1.
    int channel_index(std::string_view channel) const;
};

/// The optics of one material on its own wavelength table (nm), as `[patina.materials."<name>"]`
/// holds them: Kubelka-Munk K and S per micrometre for a layer or dielectric base, n + ik
/// for a metal, the normal-incidence reflectance and roughness of its top surface.
struct MaterialOptics {
    std::string name;
    std::string description;
    bool metal = false;
    double roughness = 0.5;  ///< perceptual, in [0, 1]
    std::vector<double> lambda_nm;
    std::vector<double> absorption_per_um, scattering_per_um;  ///< empty for a metal
    std::vector<double> specular;  ///< may be empty for a metal (then from n, k)
    std::vector<double> n, k;      ///< a metal's; else empty
};

/// One layer of `[[patina.layers]]`, bottom to top.
struct PatinaLayer {
    std::string material;
    std::string map;            ///< a name in [maps]
    std::string channel;        ///< the map's channel holding the thickness (µm)
    int channel_index = 0;      ///< its index in the map's `channels` (= in the file)
    std::string layer_map;      ///< the layer alone, as a one-channel map (may be empty)
    std::string made_by;
    double mean_um = 0.0, max_um = 0.0, coverage = 0.0;
};

/// `[patina]`: a stack grown by a patina script at one time step.
struct PatinaTable {
    std::string script;
    double time_years = 0.0;
    std::string base;
    std::string thickness_units = "um";
    std::string total_thickness = "total_thickness";  ///< a name in [maps]
    std::string preview;                              ///< a PNG beside the manifest, or none
    std::vector<PatinaLayer> layers;
    std::map<std::string, MaterialOptics> materials;  ///< the base's and every layer's
};

/// The maps of a flattened stack (`patina-texgen flatten`), by name: an ordinary BRDF's
/// and glTF's two-lobe reduction (docs/flatten.md).
inline constexpr const char* kDiffuseAlbedoMap = "diffuse_albedo";
inline constexpr const char* kHeightMap = "height";
inline constexpr const char* kNormalMap = "normal";
inline constexpr const char* kGltfBaseColorMap = "gltf_base_color";
inline constexpr const char* kGltfMetallicRoughnessMap = "gltf_metallic_roughness";
inline constexpr const char* kGltfClearcoatMap = "gltf_clearcoat";
/// What a glTF export reads of a flattened stack, in this order.
inline constexpr std::array<const char*, 5> kGltfExportMaps = {
    kGltfBaseColorMap, kGltfMetallicRoughnessMap, kGltfClearcoatMap, kNormalMap, kHeightMap};

/// One interface's maps in `[flatten] interfaces`.
struct FlattenInterface {
    std::string specular, roughness;
};

/// `[flatten]`: what a flattened stack's maps are, for a person or a pipeline.
struct FlattenTable {
    std::string stack;        ///< the patina stack flattened (relative to the manifest)
    std::string color_space;  ///< of the colour maps
    double texel_size_m = 0.0;
    double normal_scale = 1.0;
    /// The renderer the glTF maps are fitted for ("khronos", "blender"); empty in a
    /// manifest written before the fit (the two-lobe reduction alone).
    std::string gltf_target;
    std::vector<FlattenInterface> interfaces;
};

struct TextureStack {
    std::filesystem::path manifest;  ///< the stack.toml read
    int format = 1;
    std::string generator;
    std::map<std::string, StackMap> maps;
    std::optional<PatinaTable> patina;
    std::optional<FlattenTable> flatten;

    std::filesystem::path folder() const { return manifest.parent_path(); }
    /// The map `name`; throws naming the manifest when it is not listed.
    const StackMap& map(const std::string& name) const;
};

/// A time series of stacks, series.toml beside their folders (written by
/// `patina-texgen patina --times`): `[series] script`, `steps = [{time_years, folder}]`.
inline constexpr const char* kSeriesManifest = "series.toml";

struct SeriesStep {
    double time_years = 0.0;
    std::string folder;  ///< relative to the series' folder, e.g. "t30"
};

struct StackSeries {
    std::filesystem::path manifest;  ///< the series.toml read
    std::string script;
    std::vector<SeriesStep> steps;   ///< in ascending time

    std::filesystem::path folder() const { return manifest.parent_path(); }
};

/// Read `path` (a series folder or its series.toml). Throws "file:line:column: what" for a
/// malformed file, no steps, times that do not ascend or a step folder that does not exist.
StackSeries read_stack_series(const std::filesystem::path& path);

/// The folder of the step at `time_years` in a series that reaches `last_years`: "t06" for
/// 6 of 30, the times padded to one width, decimals only when a time has them ("t06.500").
std::string series_step_folder(double time_years, double last_years);

/// series.toml's text for `series` (its `manifest` is not used).
std::string stack_series_text(const StackSeries& series);

/// Read a stack: `path` is its folder or its stack.toml. Checks the format version
/// (check_stack_format), every map entry, and a `[patina]` table when there is one: its
/// base and layers, a layer's map and channel (a name in the map's `channels`, or an index
/// into it; none: the map's first channel), the optics of every material it names, and that
/// the files of the maps its layers read exist. Throws std::runtime_error
/// "file:line:column: what" (or "file: what"); a folder holding a time series (series.toml)
/// but no stack.toml is named as such.
TextureStack read_texture_stack(const std::filesystem::path& path);

/// The stack's `[patina]` table; throws naming the manifest when it has none (not a stack
/// written by `patina-texgen patina`).
const PatinaTable& patina_of(const TextureStack& stack);

/// The tables the writers store: `[maps.<name>]` (without its name), a material of
/// `[patina.materials]`, and `[patina]` itself (with its materials).
toml::table to_toml(const StackMap& map);
toml::table to_toml(const MaterialOptics& material);
toml::table to_toml(const PatinaTable& patina);
toml::table to_toml(const FlattenTable& flatten);

/// Parse one material table (as read_texture_stack does); throws naming file and key.
MaterialOptics material_from_toml(const std::filesystem::path& file, const std::string& name,
                                  const toml::table& table);

/// Where two descriptions of a material differ beyond `relative` tolerance ("specular at
/// 550 nm: 0.04 against 0.05"), or an empty string when they agree.
std::string optics_difference(const MaterialOptics& a, const MaterialOptics& b,
                              double relative = 1e-6);

}  // namespace patina::formats
