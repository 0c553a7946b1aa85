// Progress on stderr with the elapsed time and an ETA, throttled to two lines a second;
// shared by the renderer and the texgen bakers.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace patina {

class Progress {
public:
    /// `label` starts each line ("render", "ao", ...); `quiet` prints nothing.
    Progress(size_t total, bool quiet, std::string label = "render");
    /// `units` of work done (thread-safe).
    void step(size_t units = 1);
    /// End the progress line (call once, after the last step).
    void finish();
    double seconds() const;

private:
    using clock = std::chrono::steady_clock;
    size_t total_;
    bool quiet_;
    std::string label_;
    clock::time_point start_;
    std::atomic<size_t> done_{0};
    std::mutex mutex_;
    double last_ = -1.0;
    bool printed_ = false;
};

}  // namespace patina
