#include "texgen/cli/mesh_options.h"

#include "core/cli_errors.h"

#include <fmt/format.h>

#include <stdexcept>

namespace patina::texgen {

namespace {

    /// A CLI11 validator from a parser that throws std::invalid_argument.
    template <typename Parse> CLI::Validator parsed_by(Parse parse, std::string description)
    {
        return CLI::Validator(
            [parse](std::string& text) -> std::string {
                try {
                    parse(text);
                } catch (const std::invalid_argument& e) {
                    return e.what();
                }
                return {};
            },
            std::move(description));
    }

} // namespace

void add_mesh_convention_options(CLI::App& command, MeshConventionOptions& o)
{
    command
        .add_option_function<std::string>(
            "--up", [&o](const std::string& text) { o.up = parse_axis(text, "--up"); },
            "the mesh file's up axis (x, y, z, -x, -y, -z), where it differs from what the file "
            "declares (FBX, COLLADA and glTF declare theirs; OBJ, PLY and STL are taken as +y)")
        ->check(parsed_by([](const std::string& t) { parse_axis(t, "--up"); }, "AXIS"));
    CLI::Option* unit =
        command
            .add_option_function<std::string>(
                "--unit",
                [&o](const std::string& text) { o.metres_per_unit = parse_unit(text, "--unit"); },
                "the mesh file's length unit (m, cm, mm, in, ft, ...), where it differs from what "
                "the file declares (FBX, COLLADA and glTF declare theirs; others are taken as "
                "metres)")
            ->check(parsed_by([](const std::string& t) { parse_unit(t, "--unit"); }, "UNIT"));
    command
        .add_option_function<double>(
            "--scale", [&o](double metres) { o.metres_per_unit = metres; },
            "metres per unit of the mesh file, for a unit --unit does not name")
        ->check(patina::positive)
        ->excludes(unit);
    command
        .add_option("--uv-set", o.uv_set,
                    "the mesh file's uv set to bake into, from 0 (the first); a set made for "
                    "weathering, as `patina-texgen unwrap` adds, keeps the artist's own uvs for "
                    "their textures")
        ->check(CLI::Range(0, 7));
}

} // namespace patina::texgen
