// Runs a SampleBaker over sample groups with TBB: deterministic (per-sample generators
// hashed from the seed, fixed reduction order), with progress on stderr and cancellation.
#pragma once

#include "core/progress.h"
#include "texgen/bake/sample_baker.h"

#include <cstdint>
#include <vector>

namespace patina::texgen {

struct BakeRun {
    uint64_t seed = 0;
    /// Distinguishes the sample streams of different UDIM tiles (pass the UDIM number).
    uint64_t stream = 0;
    Progress* progress = nullptr;  ///< stepped once per group (may be null)
};

/// Values of every group, group-major: result[g * channels + c] is the mean over the
/// group's samples (0 for an empty group). Polls the cancellation flag and throws
/// patina::Cancelled when it is set.
std::vector<float> bake_groups(const SampleGroups& groups, const SampleBaker& baker,
                               const BakeRun& run);

}  // namespace patina::texgen
