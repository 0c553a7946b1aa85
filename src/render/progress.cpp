#include "render/progress.h"

#include <cstdio>

namespace patina::render {

Progress::Progress(size_t total, bool quiet) : total_(total), quiet_(quiet), start_(clock::now()) {}

void Progress::step()
{
    const size_t done = ++done_;
    if (quiet_)
        return;
    std::lock_guard lock(mutex_);
    const double elapsed = seconds();
    if (done != total_ && elapsed - last_ < 0.5)
        return;
    last_ = elapsed;
    const double eta =
        elapsed / static_cast<double>(done) * static_cast<double>(total_ - std::min(done, total_));
    std::fprintf(stderr, "\rrender: %5.1f%%  elapsed %.1fs  ETA %.1fs   ",
                 100.0 * static_cast<double>(done) / static_cast<double>(total_), elapsed, eta);
    printed_ = true;
}

void Progress::finish()
{
    if (!quiet_ && printed_)
        std::fprintf(stderr, "\n");
}

double Progress::seconds() const
{
    return std::chrono::duration<double>(clock::now() - start_).count();
}

}  // namespace patina::render
