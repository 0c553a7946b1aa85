// The tasks of a texgen series on a farm (docs/farm.md "Texgen series"), as patina-texgen
// plans them itself: `patina-texgen patina|fade|stone ... --plan` prints this TOML, and
// patina-farm copies it into its job folder's job.toml. patina-texgen is the one place that
// knows its options, their limits and its snapshot schedule; the farm only runs the tasks.
//
//   [plan]                    (in job.toml the same keys sit in [job], beside its own)
//   command = "patina"        patina, fade or stone
//   output = "/abs/urban"     the series' folder
//   chained = false           true: task i resumes task i - 1's checkpoint (stone)
//   [[task]]                  in the order they run
//   label = "t = 12 y"
//   args = ["patina", ...]    patina-texgen's arguments, without the program
//   outputs = ["/abs/urban/t12"]   the folders and files it writes (absolute)
//   time_years = 12.0         a patina step's time (patina only)
//   folder = "t12"            the step's folder in the series (patina, fade)
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace patina::formats {

struct TexgenPlanTask {
    std::string label;
    std::vector<std::string> args;
    std::vector<std::filesystem::path> outputs;
    std::optional<double> time_years;
    std::string folder;
};

struct TexgenPlan {
    std::string command;
    std::filesystem::path output;
    bool chained = false;
    std::vector<TexgenPlanTask> tasks;
};

/// The plan's keys (command, output, chained) for a header table, and its [[task]] array.
void add_plan_keys(toml::table& header, const TexgenPlan& plan);
toml::array plan_tasks(const TexgenPlan& plan);

/// The plan as `patina-texgen ... --plan` prints it.
std::string texgen_plan_text(const TexgenPlan& plan);

/// The plan from `header` (the table with command, output and chained; `extra_keys` are
/// the other keys it may hold) and `root`'s [[task]] array. Throws
/// "file:line:column: what" for an unknown key, a missing or mistyped value, or no tasks.
TexgenPlan read_texgen_plan(const std::filesystem::path& file, const toml::table& header,
                            const toml::table& root,
                            std::initializer_list<const char*> extra_keys = {});

/// The plan printed by `patina-texgen ... --plan` (`source` names it in errors).
TexgenPlan parse_texgen_plan(std::string_view text, const std::filesystem::path& source);

}  // namespace patina::formats
