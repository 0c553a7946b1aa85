#include "core/progress.h"

#include "core/cancel.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <string>

namespace patina {

namespace {
    /// Whether the last thing written to stderr by a Progress was a line ending in '\r'.
    std::atomic<bool> progress_line_open{false};
}  // namespace

void end_progress_line()
{
    if (progress_line_open.exchange(false)) {
        std::fputc('\n', stderr);
        std::fflush(stderr);
    }
}

void print_warning(const std::string& label, const std::string& message)
{
    end_progress_line();
    std::fprintf(stderr, "%s: warning: %s\n", label.c_str(), message.c_str());
}

Progress::Progress(size_t total, bool quiet, std::string label)
    : total_(total), quiet_(quiet), label_(std::move(label)), start_(clock::now())
{
    signal_point("setup");
}

void Progress::step(size_t units)
{
    const size_t done = done_ += units;
    if (const size_t half = (total_ + 1) / 2; done - units < half && done >= half)
        signal_point("compute");
    if (quiet_ || total_ == 0)
        return;
    std::lock_guard lock(mutex_);
    const double elapsed = seconds();
    if (done < total_ && elapsed - last_ < 0.5)
        return;
    last_ = elapsed;
    const size_t clamped = std::min(done, total_);
    const double eta = elapsed / static_cast<double>(std::max<size_t>(clamped, 1)) *
                       static_cast<double>(total_ - clamped);
    // The last line carries the whole run's time: to the hundredth (benchmarks read it).
    std::fprintf(stderr, clamped == total_ ? "\r%s: %5.1f%%  elapsed %.2fs  ETA %.1fs   "
                                           : "\r%s: %5.1f%%  elapsed %.1fs  ETA %.1fs   ",
                 label_.c_str(),
                 100.0 * static_cast<double>(clamped) / static_cast<double>(total_), elapsed, eta);
    printed_ = true;
    progress_line_open = true;
}

void Progress::finish()
{
    if (!quiet_ && printed_)
        end_progress_line();
}

double Progress::seconds() const
{
    return std::chrono::duration<double>(clock::now() - start_).count();
}

}  // namespace patina
