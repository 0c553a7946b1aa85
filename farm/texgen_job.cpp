#include "farm/texgen_job.h"

#include "farm/processes.h"
#include "formats/texgen_plan/texgen_plan.h"
#include "formats/toml_location.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <optional>
#include <sstream>
#include <stdexcept>

namespace patina::farm {

namespace fs = std::filesystem;

TexgenJob plan_texgen_job(const fs::path& folder, const std::vector<std::string>& args,
                          const fs::path& texgen, const fs::path& farm)
{
    if (args.empty())
        throw std::invalid_argument("no patina-texgen command after '--' (patina or stone)");
    TexgenJob job;
    job.folder = fs::absolute(folder).lexically_normal();
    job.command = args.front();
    job.texgen = texgen;
    job.farm = farm;
    job.cwd = fs::current_path();
    if (job.command != "patina" && job.command != "fade" && job.command != "stone")
        throw std::invalid_argument(fmt::format(
            "patina-texgen {}: a farm runs the series of 'patina' (--times), 'fade' (a list of "
            "--duration or --dose) and 'stone' (--steps)",
            job.command));
    // The farm cuts a stone run and chains its segments with these itself.
    if (job.command == "stone")
        for (const std::string& a : args)
            for (const char* own : {"--until", "--resume", "--checkpoint"})
                if (a == own || a.starts_with(std::string(own) + "="))
                    throw std::invalid_argument(fmt::format(
                        "{}: the farm cuts a stone run into segments and sets it itself", own));
    // patina-texgen plans its own tasks: its options, limits and schedules in one place.
    std::vector<std::string> argv{texgen.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    argv.push_back("--plan");
    if (job.command == "stone")
        argv.insert(argv.end(), {"--plan-checkpoints", (job.folder / "checkpoints").string()});
    std::string out, err;
    if (run_capturing(argv, &out, &err) != 0) {
        // Its own message, without its "patina-texgen: error: " prefix.
        std::string message = err.substr(0, err.find('\n'));
        if (const size_t at = message.find("error: "); at != std::string::npos)
            message = message.substr(at + 7);
        throw std::invalid_argument(message.empty() ? "patina-texgen --plan failed" : message);
    }
    const formats::TexgenPlan plan = formats::parse_texgen_plan(out, "patina-texgen --plan");
    job.output = plan.output;
    job.chained = plan.chained;
    for (const formats::TexgenPlanTask& t : plan.tasks)
        job.tasks.push_back({t.label, t.args, t.outputs, t.time_years.value_or(0.0), t.folder});
    return job;
}

JobShape texgen_job_shape(const TexgenJob& job)
{
    return {job.folder, job.farm, fmt::format("{} {}", job.command, job.output.filename().string()),
            job.tasks.size(), job.chained};
}

namespace {

    formats::TexgenPlan plan_of(const TexgenJob& job)
    {
        formats::TexgenPlan plan{job.command, job.output, job.chained, {}};
        for (const TexgenTask& t : job.tasks)
            plan.tasks.push_back({t.label, t.args, t.outputs,
                                  job.command == "patina" ? std::optional(t.time_years) : std::nullopt,
                                  t.folder});
        return plan;
    }

}  // namespace

std::string texgen_job_text(const TexgenJob& job)
{
    const formats::TexgenPlan plan = plan_of(job);
    toml::table header{{"kind", "texgen"},
                       {"texgen", job.texgen.string()},
                       {"farm", job.farm.string()},
                       {"cwd", job.cwd.string()},
                       {"keep_checkpoints", job.keep_checkpoints}};
    formats::add_plan_keys(header, plan);
    toml::table root{{"job", std::move(header)}, {"task", formats::plan_tasks(plan)}};
    std::ostringstream text;
    text << "# Written by patina-farm submit-texgen (docs/farm.md): the tasks in the order of\n"
            "# their index (SLURM_ARRAY_TASK_ID, or the chain's order), each a patina-texgen\n"
            "# command run from `cwd` and the outputs it writes, as patina-texgen planned them.\n"
         << root << "\n";
    return text.str();
}

std::string job_kind(const fs::path& folder)
{
    const toml::table root = parse_job_file(folder);
    const std::string kind = root["job"]["kind"].value_or(std::string());
    if (kind.empty())
        throw std::runtime_error(
            fmt::format("{}: no [job] kind: not a job folder of patina-farm",
                        (folder / "job.toml").string()));
    return kind;
}

TexgenJob read_texgen_job(const fs::path& folder)
{
    const toml::table root = parse_job_file(folder);
    const fs::path file = folder / "job.toml";
    const toml::table* j = root["job"].as_table();
    if (!j || (*j)["kind"].value_or(std::string()) != "texgen")
        throw std::runtime_error(fmt::format("{}: no [job] of kind \"texgen\"", file.string()));
    formats::toml_check_keys(file, root, "", {"job", "task"});
    const formats::TexgenPlan plan =
        formats::read_texgen_plan(file, *j, root,
                                  {"kind", "texgen", "farm", "cwd", "keep_checkpoints"});
    TexgenJob job;
    job.folder = fs::absolute(folder).lexically_normal();
    job.command = plan.command;
    job.texgen = (*j)["texgen"].value_or(std::string());
    job.farm = (*j)["farm"].value_or(std::string());
    job.cwd = (*j)["cwd"].value_or(std::string());
    if (j->get("keep_checkpoints"))
        job.keep_checkpoints = formats::toml_value<bool>(file, *j, "keep_checkpoints", "job.");
    job.output = plan.output;
    job.chained = plan.chained;
    for (const formats::TexgenPlanTask& t : plan.tasks)
        job.tasks.push_back({t.label, t.args, t.outputs, t.time_years.value_or(0.0), t.folder});
    return job;
}

}  // namespace patina::farm
