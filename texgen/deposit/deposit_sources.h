// Deposit sources: where airborne deposits (soot, dust, salts) come from. Dorsey et al. 1999
// §6: "The deposit maps were computed with accessibility combined with visibility to area
// deposit sources". A source is a sphere, a disc, a rectangle (area sources at a finite
// distance) or a directional source with a cone of directions (deposits carried from far
// away, e.g. by a prevailing wind), each with a strength.
//
// On the command line (`--source`, repeatable), one source is a type and key=value pairs,
// vectors as comma-separated numbers:
//
//     sphere center=X,Y,Z radius=R [strength=S]
//     disc center=X,Y,Z normal=X,Y,Z radius=R [strength=S]
//     rectangle corner=X,Y,Z edge1=X,Y,Z edge2=X,Y,Z [strength=S]
//     directional direction=X,Y,Z [spread_deg=A] [strength=S]
//
// In a TOML file (`--sources FILE.toml`) the same keys, one [[source]] table each:
//
//     [[source]]
//     type = "sphere"
//     center = [0.0, 5.0, 0.0]
//     radius = 1.0
//
// Keys are strict: an unknown, missing or malformed key is an error naming the file, line and
// key (or the --source text).
#pragma once

#include <Imath/ImathVec.h>

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen {

struct DepositSource {
    enum class Kind { Sphere, Disc, Rectangle, Directional };
    Kind kind = Kind::Sphere;
    Imath::V3f center{0.0f};             ///< sphere, disc
    float radius = 0.0f;                 ///< sphere, disc (m)
    Imath::V3f normal{0.0f, 1.0f, 0.0f}; ///< disc (unit; the disc deposits on both sides)
    Imath::V3f corner{0.0f};             ///< rectangle: corner + s edge1 + t edge2, s, t in [0, 1]
    Imath::V3f edge1{0.0f}, edge2{0.0f};
    Imath::V3f direction{0.0f, -1.0f, 0.0f}; ///< directional: the direction deposits travel
    float spread_deg = 0.0f;                 ///< directional: cone half-angle, [0, 90)
    float strength = 1.0f;                   ///< >= 0, multiplies the source's visibility

    /// The source in the command-line syntax (for the map's parameters).
    std::string describe() const;
};

/// Parse one `--source` value. Throws std::runtime_error "--source '<text>': <what>".
DepositSource parse_source_option(const std::string& text);

/// Read every [[source]] of a TOML file. Throws std::runtime_error "<file>:<line>:<col>:
/// <what>" naming the key for a syntax error, an unknown or missing key, a wrong type or an
/// out-of-range value; "<file>: ..." when the file is missing or holds no source.
std::vector<DepositSource> load_sources_file(const std::filesystem::path& path);

} // namespace patina::texgen
