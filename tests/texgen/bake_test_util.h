// Shared by the texgen baker tests.
#pragma once

#include "texgen/bake/bake_driver.h"

#include <tbb/global_control.h>

#include <vector>

namespace patina::test {

/// bake_groups with TBB limited to `threads` workers (determinism tests compare 1 and 2).
inline std::vector<float> bake_with_threads(const texgen::SampleGroups& groups,
                                            const texgen::SampleBaker& baker,
                                            const texgen::BakeRun& run, int threads)
{
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(threads));
    return texgen::bake_groups(groups, baker, run);
}

}  // namespace patina::test
