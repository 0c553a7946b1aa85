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

/// End a progress line left open on stderr (a line that ended in a carriage return), so
/// that what follows, an error or a warning, starts on its own line. Does nothing when no
/// progress line is open. Every tool's error edge calls it before its message.
void end_progress_line();

/// Print "<label>: warning: <message>" on a line of its own on stderr (after
/// end_progress_line).
void print_warning(const std::string& label, const std::string& message);

}  // namespace patina
