#pragma once
// Running the real `bladestab` program from a test, and the input-error contract its refusals must
// keep (include/bladestab/input_error.hpp):
//   - exit status exactly 2 (1 means an internal failure, a signal means a crash),
//   - nothing on stdout,
//   - exactly one line on stderr, "bladestab: error: ...", naming the offending key or option, the
//     offending value and what is allowed.
#include <filesystem>
#include <string>
#include <vector>

namespace testing_support {

// A private scratch directory for this test process (captured output, edited scenes, --out),
// removed at exit.
const std::filesystem::path& scratch();

std::string read_text(const std::filesystem::path& path);

struct Outcome {
  std::string command;     // for messages, shell-quoted
  int wait_status = 0;     // as waitpid returns it
  bool timed_out = false;  // killed after the time allowed
  double seconds = 0;      // wall time
  std::string out, err;
  bool drawer_seen = false;      // the chart drawer (a python3 child) was found and frozen
  bool drawer_outlived = false;  // it was still there after the program had ended
};

struct RunOptions {
  double timeout_seconds = 60;  // then SIGKILL
  double interrupt_after = -1;  // > 0: SIGINT after this many seconds, as Ctrl-C would
  std::string stdout_path;      // instead of capturing stdout (e.g. /dev/full)
  // While a chart is drawn: once the program's python3 child runs, it is frozen (SIGSTOP), so the
  // stop lands mid-drawing whatever the machine's speed; then `signal_while_drawing` (if not 0) is
  // sent to the program, or to its process group (as Ctrl-C on a terminal) with `to_process_group`.
  // After the program has ended the drawer is continued (SIGCONT) and awaited, so an orphan has
  // its say on stderr and in the files.
  bool freeze_drawer = false;
  int signal_while_drawing = 0;
  bool to_process_group = false;
  long max_file_bytes = -1;  // > 0: RLIMIT_FSIZE of the program (SIGXFSZ ignored): writes past it fail
};

// Runs bladestab with `args`, stdin from /dev/null, stdout and stderr captured.
Outcome run_bladestab(const std::vector<std::string>& args, const RunOptions& options = {});

// "exit status 2", "killed by signal 11", "timed out after 10 s".
std::string describe(const Outcome& o);

// Runs `args` and checks the contract above with Catch; each entry of `expected` must occur in the
// error line, where an entry "a|b" is satisfied by either a or b. Returns the outcome.
Outcome expect_rejected(const std::vector<std::string>& args, const std::vector<std::string>& expected,
                        const RunOptions& options = {});

}  // namespace testing_support
