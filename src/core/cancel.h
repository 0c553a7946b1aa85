// Cancellation of long work: SIGINT / SIGTERM set a flag that loops poll, so a Ctrl-C or a
// farm kill unwinds through the normal error path (temporary files removed, no output
// renamed into place) instead of dying half-way through a write.
#pragma once

#include <stdexcept>
#include <string>

namespace patina {

/// Thrown by throw_if_cancelled(); the command-line edge turns it into exit status 130.
class Cancelled : public std::runtime_error {
public:
    Cancelled() : std::runtime_error("cancelled (interrupt or terminate signal)") {}
    explicit Cancelled(const std::string& what) : std::runtime_error(what) {}
};

/// A signal stopped a run that keeps checkpoints after it wrote one (and the outputs it
/// belongs to); the message names the file to --resume from. Exit status 130 too.
class CheckpointWritten : public Cancelled {
public:
    using Cancelled::Cancelled;
};

/// Route SIGINT and SIGTERM to the cancellation flag. A second signal terminates at once,
/// for a process stuck outside a polling loop; one within 0.25 s of the first is taken for
/// the same signal delivered twice (timeout(1) signals the process, then its group).
void install_cancel_handler();
/// True once a signal arrived (or request_cancel was called).
bool cancel_requested();
/// Set the flag by hand (tests).
void request_cancel();
/// Clear the flag (tests; patina-render after it decided to write a checkpoint).
void reset_cancel();
/// Throw Cancelled if the flag is set.
void throw_if_cancelled();

/// Fault injection for the interruption tests: when $PATINA_TEST_SIGNAL_AT names `phase`,
/// the process sends itself SIGTERM here, once, exactly as a farm's kill would arrive.
/// The phases: "setup" (inputs loaded, compute about to start: Progress is made), "compute"
/// (half of a Progress done), "write" (the first output file is staged).
void signal_point(const char* phase);

/// While one lives, a second SIGINT/SIGTERM does not terminate the process at once: it is
/// held until the last HoldTermination ends, then carried out. A commit's renames are never
/// cut half-way. (The first signal only sets the flag, as always.)
class HoldTermination {
public:
    HoldTermination();
    ~HoldTermination();
    HoldTermination(const HoldTermination&) = delete;
    HoldTermination& operator=(const HoldTermination&) = delete;
};

}  // namespace patina
