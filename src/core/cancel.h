// Cancellation of long work: SIGINT / SIGTERM set a flag that loops poll, so a Ctrl-C or a
// farm kill unwinds through the normal error path (temporary files removed, no output
// renamed into place) instead of dying half-way through a write.
#pragma once

#include <stdexcept>

namespace patina {

/// Thrown by throw_if_cancelled(); the command-line edge turns it into exit status 130.
class Cancelled : public std::runtime_error {
public:
    Cancelled() : std::runtime_error("cancelled (interrupt or terminate signal)") {}
};

/// Route SIGINT and SIGTERM to the cancellation flag (a second signal of the same kind
/// terminates at once, for a process stuck outside a polling loop).
void install_cancel_handler();
/// True once a signal arrived (or request_cancel was called).
bool cancel_requested();
/// Set the flag by hand (tests).
void request_cancel();
/// Clear the flag (tests).
void reset_cancel();
/// Throw Cancelled if the flag is set.
void throw_if_cancelled();

}  // namespace patina
