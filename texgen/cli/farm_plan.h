// `--plan` of the commands a farm cuts into tasks (patina --times, fade with a list of
// durations or doses, stone --steps): the tasks as formats/texgen_plan/texgen_plan.h prints them, so
// the farm runs what patina-texgen itself plans, with its own limits and schedules.
#pragma once

#include "formats/texgen_plan/texgen_plan.h"

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace patina::texgen {

/// Records the command line (main does, before parsing).
void set_command_line(int argc, const char* const* argv);

/// The command line after the program's name ("patina", "urban.patina", "--times", ...),
/// without `--plan` and the plan's own options.
std::vector<std::string> task_arguments();

/// `args` with the option `names` set to `value` ("--out X" and "--out=X" both; every
/// occurrence; appended as names[0] when absent).
std::vector<std::string> with_option(std::vector<std::string> args,
                                     std::initializer_list<std::string_view> names,
                                     const std::string& value);

/// Prints `plan` on stdout (texgen_plan_text).
void print_plan(const formats::TexgenPlan& plan);

}  // namespace patina::texgen
