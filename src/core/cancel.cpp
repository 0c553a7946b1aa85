#include "core/cancel.h"

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <cstring>

#include <time.h>

namespace patina {

namespace {

std::atomic<bool> g_cancel{false};
std::atomic<int> g_holds{0};            ///< live HoldTermination objects
std::atomic<int> g_held_signal{0};      ///< a second signal that arrived while held
std::atomic<long long> g_first_ns{0};   ///< when the first signal arrived (monotonic)
/// A second signal sooner than this after the first is the same one delivered twice: tools
/// like timeout(1) signal the process and then its whole process group.
constexpr long long kDuplicateWindowNs = 250'000'000;
static_assert(std::atomic<long long>::is_always_lock_free, "the signal handler needs a lock-free time");

long long monotonic_ns()
{
    timespec t{};
    ::clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe
    return static_cast<long long>(t.tv_sec) * 1'000'000'000LL + t.tv_nsec;
}
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free count");

void terminate_by(int signal_number)
{
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

extern "C" void on_cancel_signal(int signal_number)
{
    const long long now = monotonic_ns();
    if (!g_cancel.exchange(true)) {
        g_first_ns.store(now);
        return;
    }
    if (now - g_first_ns.load() < kDuplicateWindowNs)
        return;
    // Second signal: the user insists; restore the default action and re-raise, unless a
    // commit is moving files into place (then when it is done).
    if (g_holds.load() > 0)
        g_held_signal.store(signal_number);
    else
        terminate_by(signal_number);
}

}  // namespace

void install_cancel_handler()
{
    std::signal(SIGINT, on_cancel_signal);
    std::signal(SIGTERM, on_cancel_signal);
}

bool cancel_requested() { return g_cancel.load(std::memory_order_relaxed); }
void request_cancel() { g_cancel.store(true); }
void reset_cancel() { g_cancel.store(false); }

HoldTermination::HoldTermination() { g_holds.fetch_add(1); }

HoldTermination::~HoldTermination()
{
    if (g_holds.fetch_sub(1) == 1) {
        if (const int held = g_held_signal.exchange(0))
            terminate_by(held);
    }
}

void signal_point(const char* phase)
{
    static std::atomic<bool> sent{false};
    const char* wanted = std::getenv("PATINA_TEST_SIGNAL_AT");
    if (wanted && std::strcmp(wanted, phase) == 0 && !sent.exchange(true))
        std::raise(SIGTERM);
}

void throw_if_cancelled()
{
    if (cancel_requested())
        throw Cancelled();
}

}  // namespace patina
