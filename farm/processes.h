// Running the programs a farm job is made of (patina-render, sbatch): argv vectors, no
// shell, the exit status back.
#pragma once

#include <string>
#include <vector>

namespace patina::farm {

/// Runs `argv` (argv[0] looked up in PATH), its output and errors going where ours go.
/// Returns its exit status (128 + the signal when a signal ended it). Throws
/// std::runtime_error when it cannot be started.
int run_program(const std::vector<std::string>& argv);

/// Runs `argv` and returns what it printed on stdout; throws std::runtime_error with its
/// exit status when it fails (its stderr goes where ours goes).
std::string run_and_capture(const std::vector<std::string>& argv);

/// Runs `argv`, capturing stdout into `out` and stderr into `err`; returns its exit status.
/// Throws std::runtime_error when it cannot be started.
int run_capturing(const std::vector<std::string>& argv, std::string* out, std::string* err);

}  // namespace patina::farm
