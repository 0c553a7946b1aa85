#include "core/cancel.h"

#include <atomic>
#include <csignal>

namespace patina {

namespace {

std::atomic<bool> g_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_cancel_signal(int signal_number)
{
    if (g_cancel.exchange(true)) {
        // Second signal: the user insists; restore the default action and re-raise.
        std::signal(signal_number, SIG_DFL);
        std::raise(signal_number);
    }
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

void throw_if_cancelled()
{
    if (cancel_requested())
        throw Cancelled();
}

}  // namespace patina
