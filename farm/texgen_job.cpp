#include "farm/texgen_job.h"

#include "formats/stone_volume.h"
#include "formats/texture_stack.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace patina::farm {

namespace fs = std::filesystem;

namespace {

    /// The value of the option `names` in `args` ("--out X" or "--out=X"), if given.
    std::optional<std::string> option_value(const std::vector<std::string>& args,
                                            std::initializer_list<std::string_view> names)
    {
        std::optional<std::string> value;
        for (size_t i = 0; i < args.size(); ++i)
            for (std::string_view name : names) {
                if (args[i] == name && i + 1 < args.size())
                    value = args[i + 1];
                else if (args[i].size() > name.size() && args[i].starts_with(name) &&
                         args[i][name.size()] == '=')
                    value = args[i].substr(name.size() + 1);
            }
        return value;
    }

    /// `args` with the option `names` set to `value` (each occurrence; appended as
    /// names[0] when absent).
    std::vector<std::string> with_option(std::vector<std::string> args,
                                         std::initializer_list<std::string_view> names,
                                         const std::string& value)
    {
        bool found = false;
        for (size_t i = 0; i < args.size(); ++i)
            for (std::string_view name : names) {
                if (args[i] == name && i + 1 < args.size()) {
                    args[i + 1] = value;
                    found = true;
                } else if (args[i].size() > name.size() && args[i].starts_with(name) &&
                           args[i][name.size()] == '=') {
                    args[i] = std::string(name) + "=" + value;
                    found = true;
                }
            }
        if (!found) {
            args.emplace_back(*names.begin());
            args.push_back(value);
        }
        return args;
    }

    int int_option(const std::vector<std::string>& args, std::string_view name, int fallback)
    {
        const std::optional<std::string> v = option_value(args, {name});
        if (!v)
            return fallback;
        size_t used = 0;
        int n = 0;
        try {
            n = std::stoi(*v, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != v->size())
            throw std::invalid_argument(fmt::format("{} '{}' is not a whole number", name, *v));
        return n;
    }

    /// --times: years, ascending.
    std::vector<double> parse_times(const std::string& text)
    {
        std::vector<double> times;
        std::stringstream in(text);
        std::string item;
        while (std::getline(in, item, ',')) {
            size_t used = 0;
            double t = 0;
            try {
                t = std::stod(item, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used == 0 || used != item.size() || !std::isfinite(t) || t < 0 ||
                (!times.empty() && !(t > times.back())))
                throw std::invalid_argument(fmt::format(
                    "--times '{}': '{}' is not a time in years after the one before", text, item));
            times.push_back(t);
        }
        if (times.empty())
            throw std::invalid_argument("--times: no times given");
        return times;
    }

    TexgenJob plan_patina(TexgenJob job, const std::vector<std::string>& args)
    {
        const std::optional<std::string> times_text = option_value(args, {"--times"});
        if (!times_text)
            throw std::invalid_argument(
                "a patina series on a farm needs --times (its steps, a task each)");
        const std::vector<double> times = parse_times(*times_text);
        const std::string end = option_value(args, {"--end-time"}).value_or(fmt::format("{}", times.back()));
        job.output = fs::absolute(option_value(args, {"-o", "--out"}).value_or("patina"))
                         .lexically_normal();
        for (double t : times) {
            TexgenTask task;
            task.time_years = t;
            // One step alone is written as the stack itself, as patina-texgen does.
            task.folder = times.size() > 1 ? formats::series_step_folder(t, times.back()) : "";
            const fs::path out = task.folder.empty() ? job.output : job.output / task.folder;
            task.label = fmt::format("t = {} y", t);
            task.args = with_option(with_option(with_option(args, {"--times"}, fmt::format("{}", t)),
                                                {"--end-time"}, end),
                                    {"-o", "--out"}, out.string());
            task.outputs = {out};
            job.tasks.push_back(std::move(task));
        }
        return job;
    }

    TexgenJob plan_stone(TexgenJob job, const std::vector<std::string>& args)
    {
        for (const char* own : {"--until", "--resume", "--checkpoint"})
            if (option_value(args, {own}))
                throw std::invalid_argument(fmt::format(
                    "{}: the farm cuts a stone run into segments and sets it itself", own));
        const int cycles = int_option(args, "--cycles", 100);
        const int steps = int_option(args, "--steps", 0);
        if (steps < 1 || cycles < 1)
            throw std::invalid_argument(
                "a stone run on a farm is cut into segments between its snapshots: give "
                "--cycles N and --steps K (K >= 1), a task each");
        job.output = fs::absolute(option_value(args, {"--out"}).value_or("stone")).lexically_normal();
        job.chained = true;
        // The snapshots, as patina-texgen stone takes them: the fresh stone, then evenly.
        std::vector<int> at;
        for (int k = 0; k <= steps; ++k)
            at.push_back(static_cast<int>(int64_t(cycles) * k / steps));
        at.erase(std::unique(at.begin(), at.end()), at.end());
        auto checkpoint = [&](int cycle) {
            return job.folder / "checkpoints" / fmt::format("{}.stone",
                                                            formats::stone_snapshot_folder(cycle, cycles));
        };
        for (size_t k = 0; k + 1 < at.size(); ++k) {
            TexgenTask task;
            task.label = fmt::format("cycles {}-{}", at[k], at[k + 1]);
            task.args = args;
            task.args.insert(task.args.end(), {"--until", std::to_string(at[k + 1]),
                                               "--checkpoint", checkpoint(at[k + 1]).string()});
            if (k > 0)
                task.args.insert(task.args.end(), {"--resume", checkpoint(at[k]).string()});
            if (k == 0)
                task.outputs.push_back(job.output / formats::stone_snapshot_folder(at[0], cycles));
            task.outputs.push_back(job.output / formats::stone_snapshot_folder(at[k + 1], cycles));
            task.outputs.push_back(checkpoint(at[k + 1]));
            job.tasks.push_back(std::move(task));
        }
        return job;
    }

    /// A fade series: one stack per value of a list given to --duration or --dose.
    TexgenJob plan_fade(TexgenJob job, const std::vector<std::string>& args)
    {
        std::string option;
        for (const char* name : {"--duration", "--dose"})
            if (const auto v = option_value(args, {name}); v && v->find(',') != std::string::npos) {
                if (!option.empty())
                    throw std::invalid_argument("a fade series on a farm takes one list: "
                                                "--duration or --dose, not both");
                option = name;
            }
        if (option.empty())
            throw std::invalid_argument("a fade series on a farm needs a list, --duration "
                                        "D1,D2,... or --dose J1,J2,... (a stack each)");
        const std::optional<std::string> out = option_value(args, {"-o", "--out"});
        if (!out)
            throw std::invalid_argument("a fade series on a farm needs -o OUT (its stacks go "
                                        "into folders in it)");
        job.output = fs::absolute(*out).lexically_normal();
        std::stringstream in(*option_value(args, {option}));
        std::string value;
        std::vector<std::string> folders;
        while (std::getline(in, value, ',')) {
            // The value names the folder ("7d", "1e+06"), other characters as '_'.
            std::string folder = value;
            for (char& c : folder)
                if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '+' && c != '-')
                    c = '_';
            if (folder.empty() || std::find(folders.begin(), folders.end(), folder) != folders.end())
                throw std::invalid_argument(fmt::format("{} '{}': an empty or repeated value",
                                                        option, *option_value(args, {option})));
            folders.push_back(folder);
            TexgenTask task;
            task.label = fmt::format("{} {}", option, value);
            task.folder = folder;
            task.args = with_option(with_option(args, {option}, value), {"-o", "--out"},
                                    (job.output / folder).string());
            task.outputs = {job.output / folder};
            job.tasks.push_back(std::move(task));
        }
        return job;
    }

}  // namespace

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
    if (job.command == "patina")
        return plan_patina(std::move(job), args);
    if (job.command == "stone")
        return plan_stone(std::move(job), args);
    if (job.command == "fade")
        return plan_fade(std::move(job), args);
    throw std::invalid_argument(fmt::format(
        "patina-texgen {}: a farm runs the series of 'patina' (--times), 'fade' (a list of "
        "--duration or --dose) and 'stone' (--steps)",
        job.command));
}

JobShape texgen_job_shape(const TexgenJob& job)
{
    return {job.folder, job.farm, fmt::format("{} {}", job.command, job.output.filename().string()),
            job.tasks.size(), job.chained};
}

std::string texgen_job_text(const TexgenJob& job)
{
    toml::table root;
    root.insert_or_assign("job", toml::table{{"kind", "texgen"},
                                             {"command", job.command},
                                             {"texgen", job.texgen.string()},
                                             {"farm", job.farm.string()},
                                             {"cwd", job.cwd.string()},
                                             {"output", job.output.string()},
                                             {"chained", job.chained}});
    toml::array tasks;
    for (const TexgenTask& t : job.tasks) {
        toml::array args, outputs;
        for (const std::string& a : t.args)
            args.push_back(a);
        for (const fs::path& o : t.outputs)
            outputs.push_back(o.string());
        toml::table task{{"label", t.label}, {"args", std::move(args)}, {"outputs", std::move(outputs)}};
        if (job.command == "patina")
            task.insert_or_assign("time_years", t.time_years);
        if (!t.folder.empty())
            task.insert_or_assign("folder", t.folder);
        tasks.push_back(std::move(task));
    }
    root.insert_or_assign("task", std::move(tasks));
    std::ostringstream text;
    text << "# Written by patina-farm submit-texgen (docs/farm.md): the tasks in the order of\n"
            "# their index (SLURM_ARRAY_TASK_ID, or the chain's order), each a patina-texgen\n"
            "# command run from `cwd` and the outputs it writes.\n"
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
    auto fail = [&](const std::string& what) {
        return std::runtime_error(fmt::format("{}: {}", file.string(), what));
    };
    const toml::table* j = root["job"].as_table();
    if (!j || (*j)["kind"].value_or(std::string()) != "texgen")
        throw fail("no [job] of kind \"texgen\"");
    TexgenJob job;
    job.folder = fs::absolute(folder).lexically_normal();
    job.command = (*j)["command"].value_or(std::string());
    job.texgen = (*j)["texgen"].value_or(std::string());
    job.farm = (*j)["farm"].value_or(std::string());
    job.cwd = (*j)["cwd"].value_or(std::string());
    job.output = (*j)["output"].value_or(std::string());
    job.chained = (*j)["chained"].value_or(false);
    if (const toml::array* tasks = root["task"].as_array())
        for (const toml::node& n : *tasks) {
            const toml::table* t = n.as_table();
            if (!t)
                throw fail("a [[task]] that is not a table");
            TexgenTask task;
            task.label = (*t)["label"].value_or(std::string());
            if (const toml::array* a = (*t)["args"].as_array())
                for (const toml::node& arg : *a)
                    task.args.push_back(arg.value_or(std::string()));
            if (const toml::array* a = (*t)["outputs"].as_array())
                for (const toml::node& o : *a)
                    task.outputs.emplace_back(o.value_or(std::string()));
            task.time_years = (*t)["time_years"].value_or(0.0);
            task.folder = (*t)["folder"].value_or(std::string());
            if (task.args.empty() || task.outputs.empty())
                throw fail("a [[task]] without args or outputs");
            job.tasks.push_back(std::move(task));
        }
    if (job.tasks.empty())
        throw fail("no tasks");
    return job;
}

}  // namespace patina::farm
