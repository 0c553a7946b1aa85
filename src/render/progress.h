// Progress on stderr with the elapsed time and an ETA, throttled to two lines a second.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>

namespace patina::render {

class Progress {
public:
    Progress(size_t total, bool quiet);
    /// One unit of work done (thread-safe).
    void step();
    /// End the progress line (call once, after the last step).
    void finish();
    double seconds() const;

private:
    using clock = std::chrono::steady_clock;
    size_t total_;
    bool quiet_;
    clock::time_point start_;
    std::atomic<size_t> done_{0};
    std::mutex mutex_;
    double last_ = -1.0;
    bool printed_ = false;
};

}  // namespace patina::render
