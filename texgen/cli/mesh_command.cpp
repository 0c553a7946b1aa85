// `patina-texgen mesh`: writes the project's procedural meshes (with uvs) to a file, so the
// samples and users have something to bake without a modelling package.
#include "texgen/cli/commands.h"

#include "core/cli_errors.h"
#include "core/mesh_export.h"
#include "texgen/meshes/statue_mesh.h"
#include "texgen/meshes/tower_mesh.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

namespace patina::texgen {

namespace {

struct MeshOptions {
    std::string kind;
    std::filesystem::path out;
    float size = 2.0f;
    int resolution = 0;
};

void write_mesh(const MeshOptions& o)
{
    TriangleMesh mesh;
    if (o.kind == "statue") {
        StatueOptions statue;
        statue.height = o.size;
        if (o.resolution > 0) {
            statue.rings = o.resolution;
            statue.segments = o.resolution * 4 / 5;
        }
        mesh = make_statue(Imath::V3f(0.0f), statue);
    } else if (o.kind == "sphere") {
        const int n = o.resolution > 0 ? o.resolution : 64;
        mesh = make_uv_sphere(Imath::V3f(0.0f, 0.5f * o.size, 0.0f), 0.5f * o.size, n, 2 * n);
    } else if (o.kind == "tower") {
        TowerOptions tower;
        tower.width = 0.4f * o.size;
        tower.shaft_height = 0.55f * o.size;
        tower.roof_height = 0.45f * o.size;
        tower.eave = 0.04f * o.size;
        if (o.resolution > 0)
            tower.subdivisions = o.resolution;
        mesh = make_tower(Imath::V3f(0.0f), tower);
    } else if (o.kind == "plane") {
        mesh = make_plane(Imath::V3f(0.0f), o.size, o.resolution > 0 ? o.resolution : 1);
    } else {
        throw std::runtime_error("mesh: unknown kind '" + o.kind +
                                 "' (statue, sphere, tower, plane)");
    }
    save_mesh(o.out, mesh);
    std::fprintf(stderr, "mesh: %s, %zu triangles, %zu vertices -> %s\n", o.kind.c_str(),
                 mesh.triangle_count(), mesh.positions.size(), o.out.string().c_str());
}

}  // namespace

void register_mesh_command(CLI::App& app)
{
    auto options = std::make_shared<MeshOptions>();
    CLI::App* cmd = app.add_subcommand(
        "mesh", "write a procedural uv-mapped mesh: a fluted statue on a plinth, a uv sphere, "
                "a copper-roofed tower (square shaft, pyramid roof, one uv island per face) "
                "or a plane (y up, standing on y = 0)");
    cmd->add_option("kind", options->kind, "statue, sphere, tower or plane")
        ->required()->check(CLI::IsMember({"statue", "sphere", "tower", "plane"}));
    cmd->add_option("-o,--out", options->out, "output file (.obj, .ply, .glb, .gltf, .stl)")
        ->required();
    cmd->add_option("--size", options->size, "height of the statue, sphere or tower, side of the plane (m)")
        ->capture_default_str()->check(patina::positive);
    cmd->add_option("--resolution", options->resolution,
                    "rings of the statue or sphere, cells per side of a tower face or of the "
                    "plane (0: default)")
        ->check(patina::non_negative);
    cmd->callback([options] { write_mesh(*options); });
}

}  // namespace patina::texgen
