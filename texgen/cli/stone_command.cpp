// `patina-texgen stone`: weathered stone (Dorsey et al. 1999 §4): slabs around a closed mesh,
// the quarry, wet/dry cycles of moisture, dissolution, transport, crusts and erosion; writes
// the world-grid volume (for the slab_volume medium), the slab volume, the eroded mesh and
// surface maps, once or as a time series. The work is in texgen/stone/stone_job.h.
#include "texgen/cli/commands.h"
#include "texgen/cli/farm_plan.h"
#include "texgen/cli/mesh_options.h"

#include "core/cli_errors.h"
#include "texgen/stone/stone_job.h"

#include <fmt/format.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace patina::texgen {

namespace {

    struct StoneCommandOptions {
        stone::StoneJobOptions job;
        std::string stone = "sandstone";
        std::vector<double> rain_dir;
        double chemistry_scale = 1.0;
        int threads = 0;
        bool plan = false;
        std::filesystem::path plan_checkpoints;  ///< where the plan's segments keep checkpoints
    };

    /// The tasks of a farm (--plan): the run cut into segments between its snapshots
    /// (snapshot_cycles), each stopping at its last cycle with a checkpoint that the next
    /// resumes: a chain.
    formats::TexgenPlan stone_plan(const StoneCommandOptions& o)
    {
        const stone::StoneJobOptions& job = o.job;
        if (!job.checkpoint.empty() || !job.resume.empty() || job.until >= 0)
            throw std::runtime_error(fmt::format(
                "{}: the farm cuts a stone run into segments and sets it itself",
                !job.resume.empty() ? "--resume" : !job.checkpoint.empty() ? "--checkpoint" : "--until"));
        if (job.snapshots < 1 || job.cycles < 1)
            throw std::runtime_error(
                "a stone run on a farm is cut into segments between its snapshots: give "
                "--cycles N and --steps K (K >= 1), a task each");
        if (o.plan_checkpoints.empty())
            throw std::runtime_error("--plan needs --plan-checkpoints DIR (where the segments "
                                     "keep their checkpoints)");
        formats::TexgenPlan plan;
        plan.command = "stone";
        plan.output = std::filesystem::absolute(job.out_dir).lexically_normal();
        plan.chained = true;
        const std::filesystem::path folder =
            std::filesystem::absolute(o.plan_checkpoints).lexically_normal();
        const auto checkpoint = [&](int cycle) {
            return folder / (stone::snapshot_folder(cycle, job.cycles) + ".stone");
        };
        const std::vector<int> at = stone::snapshot_cycles(job.cycles, job.snapshots);
        const std::vector<std::string> args = task_arguments();
        for (size_t k = 0; k + 1 < at.size(); ++k) {
            formats::TexgenPlanTask task;
            task.label = fmt::format("cycles {}-{}", at[k], at[k + 1]);
            task.args = args;
            task.args.insert(task.args.end(), {"--until", std::to_string(at[k + 1]),
                                               "--checkpoint", checkpoint(at[k + 1]).string()});
            if (k > 0)
                task.args.insert(task.args.end(), {"--resume", checkpoint(at[k]).string()});
            if (k == 0)
                task.outputs.push_back(plan.output / stone::snapshot_folder(at[0], job.cycles));
            task.outputs.push_back(plan.output / stone::snapshot_folder(at[k + 1], job.cycles));
            task.outputs.push_back(checkpoint(at[k + 1]));
            plan.tasks.push_back(std::move(task));
        }
        return plan;
    }

    void run_stone(StoneCommandOptions o)
    {
        std::optional<tbb::global_control> threads;
        if (o.threads > 0)
            threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
        stone::StoneJobOptions& job = o.job;
        job.quarry.kind = stone::stone_kind_from_name(o.stone);
        // The mesh is read into Patina's world, +Y up (--up, --unit, --scale).
        job.quarry.up = job.params.up = Imath::V3d(0.0, 1.0, 0.0);
        job.params.seed = job.quarry.seed;
        // Chemistry accelerated against the hydraulic time (like a morphological factor).
        for (double& k : job.params.solubility)
            k *= o.chemistry_scale;
        job.params.crystallisation_rate *= o.chemistry_scale;
        job.params.black_crust_rate *= o.chemistry_scale;
        job.params.salt_supply *= o.chemistry_scale;
        if (o.rain_dir.size() == 3)
            job.rain_direction = Imath::V3d(o.rain_dir[0], o.rain_dir[1], o.rain_dir[2]);
        if (job.rain_direction && !(job.rain_direction->length() > 0.0))
            throw std::runtime_error("--rain-dir must not be zero");
        stone::run_stone_job(job);
    }

} // namespace

void register_stone_command(CLI::App& app)
{
    auto o = std::make_shared<StoneCommandOptions>();
    stone::StoneJobOptions& j = o->job;
    stone::StoneParameters& p = j.params;
    CLI::App* cmd = app.add_subcommand(
        "stone",
        "weather stone (Dorsey et al. 1999): slabs around a closed mesh, a procedural quarry, "
        "wet/dry cycles of moisture, dissolution, transport, crusts and erosion; writes "
        "volume.exr (world grid for the slab_volume medium), slabs.exr, eroded.obj and the "
        "stone_colour / stone_crust maps");
    cmd->add_option("--mesh", j.mesh, "the closed stone mesh (any Assimp format)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--slab-mesh", j.slab_mesh,
                    "a coarse closed mesh to build the slabs on (default: --mesh; each triangle "
                    "makes three slabs)")
        ->check(CLI::ExistingFile);
    add_mesh_convention_options(*cmd, j.convention);
    cmd->add_option("--out", j.out_dir, "output folder")->capture_default_str();
    cmd->add_option("--stone", o->stone, "granite, marble or sandstone")->capture_default_str();
    cmd->add_option("--feature-size", j.quarry.feature_size,
                    "grain size, vein spacing or bed thickness (m)")
        ->capture_default_str()
        ->check(patina::positive);
    cmd->add_option("--depth", j.depth,
                    "shell depth below the surface (m; default 15% of the largest extent)")
        ->check(patina::positive);
    cmd->add_option("--tangential-res", j.tangential_res, "voxels along each slab edge")
        ->capture_default_str()
        ->check(CLI::Range(2, 256));
    cmd->add_option("--depth-res", j.depth_res, "voxels through the shell's depth")
        ->capture_default_str()
        ->check(CLI::Range(2, 256));
    cmd->add_option("--cycles", j.cycles, "wet/dry cycles")->capture_default_str()->check(
        patina::non_negative);
    cmd->add_option("--steps", j.snapshots,
                    "write a time series: the fresh stone and N snapshots evenly over the "
                    "cycles, one folder each (cycle_0000, ...); 0: the end state into --out")
        ->capture_default_str()
        ->check(patina::non_negative);
    cmd->add_option("--wetness", j.wetness_map,
                    "wetness map from `patina-texgen wetness` (channel 'wetness'; needs uvs)");
    cmd->add_option("--rain-dir", o->rain_dir,
                    "X Y Z: without --wetness, wetness = max(0, -N . dir) (rain travelling along "
                    "dir)")
        ->expected(3);
    cmd->add_option("--wetness-value", j.wetness_value,
                    "constant wetness in [0, 1] (scales --rain-dir)")
        ->capture_default_str();
    cmd->add_option("--deposit", j.deposit_map,
                    "deposit map from `patina-texgen deposit` (channel 'deposit'): black crusts");
    cmd->add_option("--deposit-value", j.deposit_value, "constant deposit without --deposit")
        ->capture_default_str();
    cmd->add_option("--permeability-scale", p.permeability_scale,
                    "multiplies the quarry's permeability")
        ->capture_default_str();
    cmd->add_option("--gravity", p.gravity, "rho g in surface-pressure units per metre")
        ->capture_default_str();
    cmd->add_option("--wet-steps", p.wet_steps, "explicit steps per wet phase")
        ->capture_default_str();
    cmd->add_option("--dry-steps", p.dry_steps, "explicit steps per dry phase")
        ->capture_default_str();
    cmd->add_option("--erosion-events", p.erosion_events,
                    "erosion events per surface voxel per cycle")
        ->capture_default_str();
    cmd->add_option("--erosion-amount", p.erosion_amount, "density an event removes at its centre")
        ->capture_default_str();
    cmd->add_option("--black-crust-rate", p.black_crust_rate,
                    "binder turned into black crust per unit deposit and time")
        ->capture_default_str();
    cmd->add_option("--salt-supply", p.salt_supply,
                    "salt brought in per unit deposit and time in wet phases")
        ->capture_default_str();
    cmd->add_option("--chemistry-scale", o->chemistry_scale,
                    "speeds up dissolution, crystallisation, black crusts and salt supply "
                    "against the flow of water (whose step is short on fine lattices)")
        ->capture_default_str()
        ->check(patina::positive);
    cmd->add_option("--mineral-iron-scale", p.mineral_iron_scale,
                    "solid iron fraction that shows as fully iron-stained in the iron channel")
        ->capture_default_str()
        ->check(patina::positive);
    cmd->add_option("--grid", j.grid_resolution,
                    "world-grid voxels along the longest side of volume.exr")
        ->capture_default_str()
        ->check(CLI::Range(4, 2048));
    cmd->add_option("--map-resolution", j.map_resolution,
                    "texels per side of the surface maps (0: none)")
        ->capture_default_str()
        ->check(CLI::Range(0, 16384));
    cmd->add_flag("!--no-mesh", j.write_mesh, "do not write eroded.obj");
    cmd->add_option("--seed", j.quarry.seed, "quarry and erosion seed")->capture_default_str();
    cmd->add_option("--threads", o->threads, "worker threads (0: all cores)")
        ->capture_default_str();
    cmd->add_option("--checkpoint", j.checkpoint,
                    "write a checkpoint here when the run stops (at --until, at the end, or at a "
                    "SIGTERM/SIGINT: then at the next cycle, exit status 130)");
    cmd->add_option("--checkpoint-every", j.checkpoint_every,
                    "also every N cycles, each with the snapshots before it")
        ->check(patina::non_negative);
    cmd->add_option("--resume", j.resume,
                    "continue the run from a checkpoint (same inputs and parameters): bitwise "
                    "the run that never stopped")
        ->check(CLI::ExistingFile);
    cmd->add_option("--until", j.until,
                    "stop after this cycle (with --checkpoint: a segment of a run, as a farm "
                    "runs it)")
        ->check(patina::non_negative);
    cmd->add_flag("--quiet", j.quiet, "no progress on stderr");
    cmd->add_flag("--plan", o->plan,
                  "print the tasks a farm runs for this run (its segments between the "
                  "snapshots of --steps, as TOML; docs/farm.md) instead of running it");
    cmd->add_option("--plan-checkpoints", o->plan_checkpoints,
                    "with --plan: the folder where the segments keep their checkpoints")
        ->needs("--plan");
    cmd->callback([o] {
        if (o->plan)
            print_plan(stone_plan(*o));
        else
            run_stone(*o);
    });
}

} // namespace patina::texgen
