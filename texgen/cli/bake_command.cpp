#include "texgen/cli/bake_command.h"

#include "core/cli_errors.h"
#include "core/output_transaction.h"
#include "core/progress.h"
#include "texgen/stack/manifest.h"
#include "texgen/bake/bake_driver.h"
#include "texgen/cli/mesh_options.h"
#include "texgen/meshes/mesh_input.h"
#include "texgen/texels/ground.h"
#include "texgen/texels/mesh_merge.h"
#include "texgen/texels/uv_wrap.h"
#include "texgen/texels/texel_grid.h"

#include <tbb/global_control.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <stdexcept>

namespace patina::texgen {

void add_common_bake_options(CLI::App& command, CommonBakeOptions& o)
{
    command.add_option("--mesh", o.mesh, "mesh to bake (any Assimp format, with uvs)")
        ->required();
    add_mesh_convention_options(command, o.convention);
    command.add_option("--occluder", o.occluders,
                       "more geometry that casts shadows but is not baked (repeatable; read with "
                       "the mesh's --up, --unit, --scale)");
    command.add_flag("--uv-wrap", o.uv_wrap,
                     "fold triangles whose uvs lie outside the UDIM tiles (u < 0, v < 0, "
                     "u >= 10) into tile 1001, as a renderer's repeat wrapping reads them");
    command.add_flag("--ground", o.ground,
                     "a ground plane under the mesh: horizontal at its lowest point, 20 times its "
                     "widest horizontal extent across");
    command.add_option("-o,--out", o.out_dir, "output folder (stack.toml is updated there)")
        ->capture_default_str();
    command.add_option("--name", o.name, "map name, the file stem (default: the baker's)");
    command.add_option("--resolution", [&o](const CLI::results_t& r) {
        o.width = std::stoi(r.at(0));
        o.height = r.size() > 1 ? std::stoi(r.at(1)) : o.width;
        return o.width > 0 && o.height > 0;
    }, "texels per UDIM tile: SIZE or WIDTH HEIGHT (default 1024)")
        ->expected(1, 2);
    command.add_option("--supersampling", o.supersampling,
                       "sub-samples per texel along each axis")
        ->capture_default_str()->check(CLI::Range(1, 16));
    command.add_option("--seed", o.seed, "random seed (same seed, same bits)")
        ->capture_default_str();
    command.add_option("--threads", o.threads, "worker threads (0 = all cores)")
        ->check(patina::non_negative);
    command.add_option("--per-vertex", o.per_vertex,
                       "bake at the mesh's vertices and write this PLY (with a vertex "
                       "property per channel) instead of texture maps");
    command.add_option("--padding", o.padding,
                       "texels of push-pull padding across uv seams (-1: fill everything)")
        ->capture_default_str()->check(CLI::Range(-1, 1 << 20));
    command.add_flag("--half", o.half, "write half floats instead of 32-bit floats");
    command.add_flag("--quiet", o.quiet, "no progress on stderr");
}

namespace {

struct Occluder {
    std::string name;  ///< the file, or --ground
    std::vector<TriangleMesh> meshes;
};

std::string join_paths(const std::vector<std::filesystem::path>& paths)
{
    std::string s;
    for (const auto& p : paths)
        s += (s.empty() ? "" : ";") + p.string();
    return s;
}

}  // namespace

void run_bake(const CommonBakeOptions& options, const BakerFactory& make_baker, MapDescription map)
{
    std::optional<tbb::global_control> threads;
    if (options.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism,
                        static_cast<size_t>(options.threads));

    // Outputs first: a location that cannot be written, or a manifest that cannot be
    // updated, fails before the bake.
    if (!options.per_vertex.empty())
        reserve_output(options.per_vertex);
    else
        check_manifest_can_be_updated(options.out_dir);

    MeshConvention convention;
    TriangleMesh target = load_mesh_with_warnings(options.mesh, options.convention, &convention);
    if (options.uv_wrap)
        wrap_uvs_outside_udims(target);
    std::vector<Occluder> occluders;
    // Occluders are read with the mesh's --up and --unit: they come from the same pipeline.
    for (const auto& occluder_file : options.occluders)
        occluders.push_back({occluder_file.string(),
                             load_meshes(occluder_file, options.convention)});
    if (options.ground)
        occluders.push_back({"--ground", {ground_under(target)}});
    for (const Occluder& occluder : occluders)
        if (const std::string crossing = occluder_crossing(target, occluder.meshes); !crossing.empty())
            print_warning("patina-texgen", fmt::format("occluder '{}' cuts through the baked "
                                                       "mesh: {}", occluder.name, crossing));
    EmbreeScene scene;
    scene.add_mesh(target);
    for (const Occluder& occluder : occluders)
        for (const TriangleMesh& m : occluder.meshes)
            scene.add_mesh(m);
    scene.commit();

    const std::unique_ptr<SampleBaker> baker = make_baker({scene, target, scene.bounds()});
    map.channels = baker->channels();
    for (const auto& [key, value] : baker->resolved_parameters()) {
        const auto it = std::find_if(map.parameters.begin(), map.parameters.end(),
                                     [&](const auto& entry) { return entry.first == key; });
        if (it != map.parameters.end())
            it->second = value;
        else
            map.parameters.emplace_back(key, value);
    }
    if (!options.name.empty())
        map.name = options.name;
    Metadata recorded{{"mesh", options.mesh.string()}};
    record_convention(recorded, convention);
    record_uv_set(recorded, options.convention.uv_set);
    if (options.uv_wrap)
        record_uv_wrap(recorded);
    recorded.emplace_back("occluders", join_paths(options.occluders));
    if (options.ground)
        recorded.emplace_back("ground_y", ground_under(target).positions.front().y);
    recorded.emplace_back("seed", std::to_string(options.seed));
    map.parameters.insert(map.parameters.begin(), recorded.begin(), recorded.end());

    size_t rays = 0;
    size_t elements = 0;
    double seconds = 0.0;
    std::string written;
    if (!options.per_vertex.empty()) {
        const SampleGroups groups = vertex_samples(target);
        Progress progress(groups.group_count(), options.quiet, map.baker);
        const std::vector<float> values =
            bake_groups(groups, *baker, {options.seed, 0, &progress});
        progress.finish();
        seconds = progress.seconds();
        for (size_t g = 0; g < groups.group_count(); ++g)
            rays += baker->rays_per_sample(groups.group_size(g)) * groups.group_size(g);
        elements = groups.group_count();
        map.parameters.push_back({"mode", std::string("per-vertex")});
        write_vertex_map(options.per_vertex, target, map, values);
        written = options.per_vertex.string();
    } else {
        RasterOptions raster;
        raster.width = options.width;
        raster.height = options.height;
        raster.supersampling = options.supersampling;
        const std::vector<TexelGrid> tiles = rasterize_uv(target, raster);
        size_t total = 0;
        for (const TexelGrid& tile : tiles)
            total += tile.groups.group_count();
        map.parameters.push_back({"resolution", fmt::format("{}x{}", raster.width, raster.height)});
        map.parameters.push_back({"supersampling", raster.supersampling});

        Progress progress(total, options.quiet, map.baker);
        std::vector<std::vector<float>> values;
        for (const TexelGrid& tile : tiles) {
            values.push_back(bake_groups(tile.groups, *baker,
                                         {options.seed, static_cast<uint64_t>(tile.udim),
                                          &progress}));
            for (size_t g = 0; g < tile.groups.group_count(); ++g)
                rays += baker->rays_per_sample(tile.groups.group_size(g)) *
                        tile.groups.group_size(g);
        }
        progress.finish();
        seconds = progress.seconds();
        elements = total;

        MapOutputOptions output;
        output.padding = options.padding;
        output.format = options.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
        const auto files = write_texel_map(options.out_dir, map, tiles, values, output);
        record_in_manifest(options.out_dir, map, files, tiles);
        written = files.size() == 1 ? files.front().string()
                                    : fmt::format("{} files in {}", files.size(),
                                                  options.out_dir.string());
    }

    if (!options.quiet) {
        std::string ray_text;
        if (rays > 0)
            ray_text = fmt::format(", {:.1f} M rays ({:.2f} M rays/s)", rays * 1e-6,
                                   seconds > 0 ? rays * 1e-6 / seconds : 0.0);
        std::fprintf(stderr, "%s: %zu %s in %.2f s%s -> %s\n", map.baker.c_str(), elements,
                     options.per_vertex.empty() ? "texels" : "vertices", seconds,
                     ray_text.c_str(), written.c_str());
    }
}

}  // namespace patina::texgen
