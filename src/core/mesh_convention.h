// The axes and unit of a mesh file, and how its coordinates become Patina's world: +Y up,
// metres, north along -Z (docs/your-asset.md). What a file declares (FBX GlobalSettings,
// COLLADA <asset>, glTF by its specification) is honoured; what the user says (--up,
// --unit, --scale, or the scene's `up` and `unit`) overrides it, with a warning when the two
// disagree.
#pragma once

#include <Imath/ImathBox.h>
#include <Imath/ImathMatrix.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace patina {

/// A signed coordinate axis of a file: index 0, 1, 2 for x, y, z; sign +1 or -1.
struct Axis {
    int index = 1;
    int sign = 1;

    /// "+x", "-z", ...
    std::string name() const;
    bool operator==(const Axis&) const = default;
};

/// "x", "+x", "-x", "y", ... (case-insensitive). Throws std::invalid_argument "<what>: ..."
/// naming the accepted values otherwise.
Axis parse_axis(std::string_view text, std::string_view what);

/// Metres per unit of a unit name: m, cm, mm, um, km, in, ft, yd (and their long names,
/// "metre", "centimeter", "inch", "feet", ...). Throws std::invalid_argument "<what>: ..."
/// naming the accepted units otherwise.
double parse_unit(std::string_view text, std::string_view what);

/// The short name of a unit ("cm") when `metres_per_unit` is one of parse_unit's, else the
/// number with "m" ("0.3048 m" prints as "ft").
std::string unit_name(double metres_per_unit);

/// What the user says about a mesh file; an empty field leaves it to the file, then to
/// Patina's default (+Y up, metres). Also which of its uv sets Patina bakes into.
struct MeshConventionOptions {
    std::optional<Axis> up;
    std::optional<double> metres_per_unit;
    int uv_set = 0; ///< --uv-set: 0 is the file's first

    bool empty() const { return !up && !metres_per_unit && uv_set == 0; }
};

/// What a mesh file declares of itself.
struct DeclaredConvention {
    std::optional<Axis> up;
    std::optional<double> metres_per_unit;
    /// Where the declaration was read: "FBX GlobalSettings", "COLLADA <asset>", "glTF 2.0
    /// (+Y up, metres by specification)"; empty when the format declares nothing (OBJ, PLY).
    std::string source;
    /// The importer (Assimp) has already turned the file's coordinates into +Y up and
    /// metres by this declaration (COLLADA): an override must undo it first.
    bool applied_by_importer = false;
};

/// The convention a load applied: the up axis and unit, where each came from, and the
/// transform from the file's coordinates to Patina's world.
struct MeshConvention {
    Axis up;
    double metres_per_unit = 1.0;
    std::string up_from = "Patina's default";   ///< "--up", "FBX GlobalSettings", ...
    std::string unit_from = "Patina's default"; ///< "--unit", "COLLADA <asset>", ...
    /// Row vectors (Imath): p_world = p_file * file_to_world.
    Imath::M44f file_to_world;
    /// Where the options contradict the file ("the file declares +z up; --up y is used").
    std::vector<std::string> warnings;

    bool is_identity() const { return up == Axis{} && metres_per_unit == 1.0; }
    /// "up +z (FBX GlobalSettings), cm (--unit)".
    std::string describe() const;
};

/// The rotation taking the file's `up` to +Y (a quarter or half turn about x or z, so the
/// other axes keep their order: z-up (x, y, z) becomes (x, z, -y), as Blender, Assimp's
/// COLLADA reader and glTF exporters do) followed by the scale to metres.
Imath::M44f convention_matrix(Axis up, double metres_per_unit);

/// The convention to apply: each of up and unit from the options, else the file's
/// declaration, else +Y and metres; file_to_world from the file's raw coordinates (what an
/// importer that applied the declaration did is taken into account by load_meshes).
MeshConvention resolve_convention(const DeclaredConvention& declared,
                                  const MeshConventionOptions& options);

/// A warning when a mesh, already in metres, has a size that suggests a wrong unit: larger
/// than 100 m or smaller than 5 mm along its longest side. It names the unit that would
/// make it 0.05-20 m and the option that says so. Empty when the size looks plausible.
std::string implausible_size_warning(const Imath::Box3f& bounds, const MeshConvention& applied);

} // namespace patina
