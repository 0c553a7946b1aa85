// A weathering simulation's checkpoint (docs/file-formats.md "Stone checkpoints"): every
// field the cycles change, the clock and the caches the steps keep between calls, so that a
// run resumed from it is bitwise the run that was never stopped. The fields that never
// change after initialise_state (the quarry's colour, the columns' surface points, wetness
// and deposit) are rebuilt from the same inputs, which the setup fingerprint vouches for.
#pragma once

#include "texgen/stone/stone_state.h"

#include <filesystem>
#include <string>

namespace patina::texgen::stone {

/// Writes `st` to `file` (staged in the current output transaction, or at once when there
/// is none). `setup` names the run's inputs (stone_setup_fingerprint).
void write_stone_checkpoint(const std::filesystem::path& file, const StoneState& st,
                            const std::string& setup);

/// Reads `file` into `st`, which initialise_state set up from the run's inputs. Throws
/// std::runtime_error naming the file when it is not a checkpoint, is damaged (its
/// checksum), was written by a run with other inputs (`setup` differs) or for another
/// lattice.
void read_stone_checkpoint(const std::filesystem::path& file, StoneState& st,
                           const std::string& setup);

}  // namespace patina::texgen::stone
