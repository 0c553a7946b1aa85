#include "formats/texgen_plan/texgen_plan.h"

#include "formats/toml_location.h"

#include <sstream>
#include <vector>

namespace patina::formats {

namespace fs = std::filesystem;

void add_plan_keys(toml::table& header, const TexgenPlan& plan)
{
    header.insert_or_assign("command", plan.command);
    header.insert_or_assign("output", plan.output.string());
    header.insert_or_assign("chained", plan.chained);
}

toml::array plan_tasks(const TexgenPlan& plan)
{
    toml::array tasks;
    for (const TexgenPlanTask& t : plan.tasks) {
        toml::array args, outputs;
        for (const std::string& a : t.args)
            args.push_back(a);
        for (const fs::path& o : t.outputs)
            outputs.push_back(o.string());
        toml::table task{{"label", t.label}, {"args", std::move(args)}, {"outputs", std::move(outputs)}};
        if (t.time_years)
            task.insert_or_assign("time_years", *t.time_years);
        if (!t.folder.empty())
            task.insert_or_assign("folder", t.folder);
        tasks.push_back(std::move(task));
    }
    return tasks;
}

std::string texgen_plan_text(const TexgenPlan& plan)
{
    toml::table header;
    add_plan_keys(header, plan);
    toml::table root{{"plan", std::move(header)}, {"task", plan_tasks(plan)}};
    std::ostringstream text;
    text << root << "\n";
    return text.str();
}

namespace {

    std::vector<std::string> strings_of(const fs::path& file, const toml::table& table,
                                        const char* key, const std::string& where)
    {
        const toml::node* node = table.get(key);
        const toml::array* array = node ? node->as_array() : nullptr;
        if (!array || array->empty())
            toml_fail(file, node, where + key + ": a non-empty array of strings is required");
        std::vector<std::string> out;
        for (const toml::node& item : *array) {
            if (!item.is_string())
                toml_fail(file, &item, where + key + ": not a string");
            out.push_back(**item.as_string());
        }
        return out;
    }

}  // namespace

TexgenPlan read_texgen_plan(const fs::path& file, const toml::table& header,
                            const toml::table& root, std::initializer_list<const char*> extra_keys)
{
    std::vector<const char*> keys{"command", "output", "chained"};
    keys.insert(keys.end(), extra_keys.begin(), extra_keys.end());
    toml_check_keys(file, header, "", keys);
    TexgenPlan plan;
    plan.command = toml_value<std::string>(file, header, "command", "");
    plan.output = toml_value<std::string>(file, header, "output", "");
    if (header.get("chained"))
        plan.chained = toml_value<bool>(file, header, "chained", "");
    for (const toml::table* t : toml_table_array(file, root, "task")) {
        const std::string where = "task " + std::to_string(plan.tasks.size()) + ": ";
        toml_check_keys(file, *t, where, {"label", "args", "outputs", "time_years", "folder"});
        TexgenPlanTask task;
        task.label = toml_value<std::string>(file, *t, "label", where);
        task.args = strings_of(file, *t, "args", where);
        for (const std::string& o : strings_of(file, *t, "outputs", where))
            task.outputs.emplace_back(o);
        if (const toml::node* time = t->get("time_years")) {
            if (!time->is_number())
                toml_fail(file, time, where + "time_years: a number is required");
            task.time_years = time->value<double>();
        }
        if (t->get("folder"))
            task.folder = toml_value<std::string>(file, *t, "folder", where);
        plan.tasks.push_back(std::move(task));
    }
    return plan;
}

TexgenPlan parse_texgen_plan(std::string_view text, const fs::path& source)
{
    const toml::table root = parse_toml_text(text, source);
    toml_check_keys(source, root, "", {"plan", "task"});
    const toml::table* header = root["plan"].as_table();
    if (!header)
        toml_fail(source, nullptr, "no [plan]");
    return read_texgen_plan(source, *header, root);
}

}  // namespace patina::formats
