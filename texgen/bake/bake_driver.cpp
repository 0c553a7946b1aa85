#include "texgen/bake/bake_driver.h"

#include "core/cancel.h"

#include <tbb/blocked_range.h>
#include <tbb/partitioner.h>
#include <tbb/parallel_for.h>

namespace patina::texgen {

std::vector<float> bake_groups(const SampleGroups& groups, const SampleBaker& baker,
                               const BakeRun& run)
{
    const size_t channel_count = baker.channels().size();
    const size_t group_count = groups.group_count();
    std::vector<float> values(group_count * channel_count, 0.0f);
    // Blocks of at most kGrain groups (simple_partitioner: the auto partitioner would hand
    // out huge first chunks): small enough to balance, to show progress and to notice a
    // cancellation quickly, large enough that scheduling costs nothing next to the rays.
    constexpr size_t kGrain = 32;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, group_count, kGrain),
                      [&](const tbb::blocked_range<size_t>& range) {
        std::vector<double> sum(channel_count);
        std::vector<float> one(channel_count);
        for (size_t g = range.begin(); g != range.end(); ++g) {
            if (cancel_requested())
                return;
            const uint32_t first = groups.offsets[g];
            const uint32_t last = groups.offsets[g + 1];
            const size_t size = last - first;
            std::fill(sum.begin(), sum.end(), 0.0);
            for (uint32_t s = first; s != last; ++s) {
                // One stream per (seed, tile, group, sample): the bits do not depend on
                // which thread or block draws them.
                Pcg32 rng(hash_values(run.seed, run.stream, g, s - first));
                baker.evaluate(groups.samples[s], size, rng, one.data());
                for (size_t c = 0; c < channel_count; ++c)
                    sum[c] += one[c];
            }
            if (size > 0)
                for (size_t c = 0; c < channel_count; ++c)
                    values[g * channel_count + c] =
                        static_cast<float>(sum[c] / static_cast<double>(size));
        }
        if (run.progress)
            run.progress->step(range.size());
    }, tbb::simple_partitioner());
    throw_if_cancelled();
    return values;
}

}  // namespace patina::texgen
