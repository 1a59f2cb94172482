#pragma once
// Stopping a run from outside: Ctrl-C (SIGINT), SIGTERM, and the --max-seconds deadline. A stop
// ends the process at once — the numerics need no cooperation — with one line on stderr and a
// non-zero status (128 + the signal; 1 for the deadline), after ending the program's child (the
// chart drawer) and removing the temporaries of output files not yet complete (output_files.hpp):
// the files of a run are all written or none is.
#include <sys/types.h>

#include <string>

namespace bladestab::cli {

// SIGINT and SIGTERM stop the run as above.
void stop_on_signals();

// After `seconds` of wall time the run is stopped as above; `limit` names the limit in the message.
void stop_after(double seconds, const std::string& limit);

// A temporary file to remove if the run is stopped; returns its slot for forget_temporary (-1 if
// the registry is full, when the file is simply not removed).
int remember_temporary(const std::string& path);
void forget_temporary(int slot);

// The child process writing a temporary (one at a time): a stop kills it (SIGKILL) and waits until
// it has ended before the temporaries are removed, so it creates none after. Forget it (inside a
// StopDeferral) before reaping it, so a stop never signals a process id that was reused.
void remember_child(pid_t pid);
void forget_child();

// A set of output files is in place: a stop from now on says so instead of "no output files written".
void note_files_written();

// The run is ending (its answer or its one line is being written): a stop from now on waits for the
// process's end, so the last line is the run's own, never followed by a stop's.
void end_of_run();

// While one lives, a stop waits: a set of output files is being renamed into place, or a child
// started (until remember_child) or reaped (after forget_child).
class StopDeferral {
public:
  StopDeferral();
  ~StopDeferral();
  StopDeferral(const StopDeferral&) = delete;
  StopDeferral& operator=(const StopDeferral&) = delete;
};

}  // namespace bladestab::cli
