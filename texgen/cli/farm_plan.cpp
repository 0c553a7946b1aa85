#include "texgen/cli/farm_plan.h"

#include <cstdio>

namespace patina::texgen {

namespace {

    std::vector<std::string>& command_line()
    {
        static std::vector<std::string> args;
        return args;
    }

}  // namespace

void set_command_line(int argc, const char* const* argv)
{
    command_line().assign(argv + (argc > 0 ? 1 : 0), argv + argc);
}

std::vector<std::string> task_arguments()
{
    std::vector<std::string> args;
    const std::vector<std::string>& all = command_line();
    for (size_t i = 0; i < all.size(); ++i) {
        if (all[i] == "--plan")
            continue;
        if (all[i] == "--plan-checkpoints") {
            ++i;  // and its value
            continue;
        }
        if (all[i].starts_with("--plan-checkpoints="))
            continue;
        args.push_back(all[i]);
    }
    return args;
}

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

void print_plan(const formats::TexgenPlan& plan)
{
    const std::string text = formats::texgen_plan_text(plan);
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
}

}  // namespace patina::texgen
