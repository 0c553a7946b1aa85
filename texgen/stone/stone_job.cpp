#include "texgen/stone/stone_job.h"

#include "core/cancel.h"
#include "core/file_fingerprint.h"
#include "core/mesh_export.h"
#include "core/output_transaction.h"
#include "core/progress.h"
#include "formats/stone_volume/stone_volume.h"
#include "texgen/meshes/mesh_input.h"
#include "texgen/stack/surface_map.h"
#include "texgen/stone_export/eroded_mesh.h"
#include "texgen/stone/stone_checkpoint.h"
#include "texgen/stone_export/surface_maps.h"
#include "texgen/stone_export/volume_export.h"
#include "texgen/texels/mesh_merge.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace patina::texgen::stone {

namespace fs = std::filesystem;
using Imath::V3d;

std::vector<int> snapshot_cycles(int cycles, int steps)
{
    std::vector<int> at;
    if (steps > 0)
        for (int k = 0; k <= steps; ++k)
            at.push_back(static_cast<int>(static_cast<long long>(cycles) * k / steps));
    else
        at.push_back(cycles);
    at.erase(std::unique(at.begin(), at.end()), at.end());
    return at;
}

std::string snapshot_folder(int cycle, int last)
{
    return formats::stone_snapshot_folder(cycle, last);
}

namespace {

    Metadata job_metadata(const StoneJobOptions& o, const StoneState& st)
    {
        return {
            {"patina:baker", std::string("stone")},
            {"patina:stone", std::string(stone_kind_name(o.quarry.kind))},
            {"patina:seed", int(o.quarry.seed)},
            {"patina:cycles", st.cycles_done},
            {"patina:time", float(st.time)},
            {"patina:n_t", st.lattice->grid().n_t},
            {"patina:n_d", st.lattice->grid().n_d},
            {"patina:slabs", st.lattice->grid().slab_count},
            {"patina:mesh", o.mesh.string()},
            {"patina:wetness", o.wetness_map.empty() ? fmt::format("{}", o.wetness_value)
                                                     : o.wetness_map.string()},
        };
    }

    std::string fingerprint_or_empty(const fs::path& file)
    {
        return file.empty() ? std::string("-") : file_fingerprint(file);
    }

} // namespace

std::string stone_setup_fingerprint(const StoneJobOptions& o)
{
    const StoneParameters& p = o.params;
    const QuarryOptions& q = o.quarry;
    auto v3 = [](const V3d& v) { return fmt::format("{},{},{}", v.x, v.y, v.z); };
    const std::string rain = o.rain_direction ? v3(*o.rain_direction) : std::string("-");
    // Every input of the states, as text (fmt writes doubles so they read back exactly).
    const std::string text = fmt::format(
        "mesh {} slab_mesh {} up {} unit {} wetness {} {} rain {} deposit {} {}\n"
        "quarry {} {} {} {} {}\n"
        "shell {} {} {}\n"
        "moisture {} {} {} {} {} {} {}\n"
        "species {} {} {} {}\n"
        "crusts {} {}\n"
        "decay {} {} {} {} {}\n"
        "cycle {} {} seed {}\n",
        file_fingerprint(o.mesh), fingerprint_or_empty(o.slab_mesh),
        o.convention.up ? o.convention.up->name() : std::string("-"),
        o.convention.metres_per_unit ? fmt::format("{}", *o.convention.metres_per_unit)
                                     : std::string("-"),
        fingerprint_or_empty(o.wetness_map), o.wetness_value, rain,
        fingerprint_or_empty(o.deposit_map), o.deposit_value, stone_kind_name(q.kind), q.seed,
        q.feature_size, v3(q.up), q.kozeny_carman_k0, o.depth, o.tangential_res, o.depth_res,
        p.surface_pressure, p.pressure_diffusivity, p.viscosity, p.gravity, v3(p.up),
        p.permeability_scale, p.evaporation_speed, fmt::join(p.solubility, ","),
        fmt::join(p.saturation, ","), fmt::join(p.diffusivity, ","), p.crystallisation_rate,
        p.black_crust_rate, p.salt_supply, p.decay_water, p.decay_dissolution, p.erosion_events,
        p.erosion_radius, p.erosion_amount, p.wet_steps, p.dry_steps, p.seed);
    return bytes_fingerprint(text);
}

void write_stone_outputs(const fs::path& dir, const StoneState& st, const TriangleMesh& mesh,
                         const StoneJobOptions& o)
{
    check_state_finite(st);
    const Metadata meta = job_metadata(o, st);
    const Quarry quarry(o.quarry);
    const WorldVolume world = resample_to_world(st, mesh, o.grid_resolution, &quarry);
    write_world_volume(dir / "volume.exr", world, meta);
    write_slab_volume(dir / "slabs.exr", st, meta);
    if (o.write_mesh)
        save_mesh(dir / "eroded.obj", extract_eroded_surface(world));
    if (o.map_resolution > 0 && mesh.has_uvs())
        write_surface_maps(dir, st, mesh, o.map_resolution, meta);
}

void run_stone_job(const StoneJobOptions& o)
{
    const auto start = std::chrono::steady_clock::now();
    reserve_output(o.out_dir / "volume.exr");  // a bad output folder fails before the run
    if (!o.checkpoint.empty())
        reserve_output(o.checkpoint);
    const TriangleMesh mesh = load_mesh_with_warnings(o.mesh, o.convention);
    const TriangleMesh base =
        o.slab_mesh.empty() ? mesh : load_mesh_with_warnings(o.slab_mesh, o.convention);
    check_world_volume_memory(mesh, o.grid_resolution, "--grid");
    if (o.cycles < 0 || o.snapshots < 0)
        throw std::runtime_error("stone: --cycles and --steps must be >= 0");
    if (o.until > o.cycles)
        throw std::runtime_error(fmt::format("stone: --until {} is past --cycles {}", o.until,
                                             o.cycles));
    if (o.checkpoint_every < 0)
        throw std::runtime_error("stone: --checkpoint-every must be >= 0");
    if (o.checkpoint_every > 0 && o.checkpoint.empty())
        throw std::runtime_error("stone: --checkpoint-every needs --checkpoint FILE");
    const int stop = o.until >= 0 ? o.until : o.cycles;
    if (o.map_resolution > 0 && !mesh.has_uvs() && !o.quiet)
        std::fprintf(stderr, "stone: '%s' has no uvs: no surface maps\n", o.mesh.string().c_str());

    // The shell: by default 15% of the largest extent, a tenth of it outside the surface.
    Imath::Box3d box;
    for (const auto& p : mesh.positions)
        box.extendBy(V3d(p.x, p.y, p.z));
    const V3d size = box.max - box.min;
    ShellOptions shell_options;
    shell_options.depth = o.depth > 0.0 ? o.depth : 0.15 * std::max({size.x, size.y, size.z});
    shell_options.outer_margin = 1.5 * shell_options.depth / o.depth_res;
    shell_options.depth += shell_options.outer_margin;
    const SlabShell shell = build_slab_shell(base, shell_options);
    const SlabLattice lattice(shell, o.tangential_res, o.depth_res);
    if (!o.quiet)
        std::fprintf(stderr, "stone: %d slabs of %d x %d x %d voxels (%zu voxels), shell %.4g m "
                     "deep, %d slabs pulled in against folding\n", lattice.grid().slab_count,
                     o.tangential_res, o.tangential_res, o.depth_res, lattice.grid().voxel_count(),
                     shell_options.depth, shell.folded_fixes);

    // Boundary values per column: wetness and deposit at the column's surface point.
    std::vector<ColumnSurface> columns;
    {
        std::vector<float> density;
        voxelize(lattice, mesh, density, columns);
    }
    auto per_column = [&](const fs::path& map, const std::vector<std::string>& channels,
                          const char* what, float constant,
                          const std::optional<V3d>& rain) -> std::vector<float> {
        std::vector<float> v(columns.size(), constant);
        if (!map.empty()) {
            if (!mesh.has_uvs())
                throw std::runtime_error(fmt::format("{} '{}' needs a mesh with uvs ('{}' has "
                                                     "none)", what, map.string(), o.mesh.string()));
            const SurfaceMap m(map, channels, what);
            for (size_t c = 0; c < columns.size(); ++c)
                if (columns[c].hit)
                    v[c] = m.at(columns[c].uv);
        } else if (rain) {
            const V3d d = rain->normalized();
            for (size_t c = 0; c < columns.size(); ++c) {
                const auto& N = columns[c].N;
                v[c] = float(std::max(0.0, -(d.x * N.x + d.y * N.y + d.z * N.z))) * constant;
            }
        }
        return v;
    };
    std::vector<float> wetness = per_column(o.wetness_map, {"wetness"}, "wetness map",
                                            o.wetness_value, o.rain_direction);
    for (float& w : wetness)
        w = std::clamp(w, 0.0f, 1.0f);
    std::vector<float> deposit =
        per_column(o.deposit_map, {"deposit"}, "deposit map", o.deposit_value, std::nullopt);

    const Quarry quarry(o.quarry);
    StoneState st;
    initialise_state(st, lattice, mesh, quarry, o.params, std::move(wetness), std::move(deposit));
    const std::string setup =
        o.resume.empty() && o.checkpoint.empty() ? std::string() : stone_setup_fingerprint(o);
    if (!o.resume.empty()) {
        read_stone_checkpoint(o.resume, st, setup);
        if (st.cycles_done > stop)
            throw std::runtime_error(fmt::format(
                "stone: --resume '{}' is at cycle {}, past the last cycle {} of this run",
                o.resume.string(), st.cycles_done, stop));
        if (!o.quiet)
            std::fprintf(stderr, "stone: resumed at cycle %d from %s\n", st.cycles_done,
                         o.resume.string().c_str());
    }
    const int first = st.cycles_done;

    // Snapshots: the fresh stone, then evenly over the cycles; or only the end. A resumed
    // run wrote the one at its first cycle before it stopped.
    const std::vector<int> at = snapshot_cycles(o.cycles, o.snapshots);
    // A checkpoint and the snapshots before it go into place together: a run stopped later
    // loses only the cycles since.
    auto checkpoint = [&] {
        write_stone_checkpoint(o.checkpoint, st, setup);
        if (OutputTransaction* outputs = current_output_transaction())
            outputs->commit_so_far();
    };
    Progress progress(size_t(stop - first), o.quiet, "stone");
    for (int c = first; c <= stop; ++c) {
        if (std::find(at.begin(), at.end(), c) != at.end() && (c > first || o.resume.empty())) {
            const fs::path dir = o.snapshots > 0 ? o.out_dir / snapshot_folder(c, o.cycles)
                                                 : o.out_dir;
            write_stone_outputs(dir, st, mesh, o);
        }
        if (c == stop) {
            if (!o.checkpoint.empty())
                write_stone_checkpoint(o.checkpoint, st, setup);  // committed with the run
            break;
        }
        if (!o.checkpoint.empty() && cancel_requested()) {
            // A farm's preemption (SIGTERM): keep what is done, then stop as cancelled.
            reset_cancel();
            checkpoint();
            throw CheckpointWritten(fmt::format(
                "stopped at cycle {}: the snapshots so far and the checkpoint '{}' are written; "
                "--resume it to continue", c, o.checkpoint.string()));
        }
        throw_if_cancelled();
        if (!o.checkpoint.empty() && o.checkpoint_every > 0 && c > first &&
            (c - first) % o.checkpoint_every == 0)
            checkpoint();
        run_cycle(st);
        progress.step();
    }
    progress.finish();
    if (!o.quiet) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "stone: cycles %d to %d, moist depth %.4g m, %.1f s, written to %s\n",
                     first, stop, moist_depth(st), seconds, o.out_dir.string().c_str());
    }
}

} // namespace patina::texgen::stone
