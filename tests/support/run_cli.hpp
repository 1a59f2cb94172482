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
};

struct RunOptions {
  double timeout_seconds = 60;  // then SIGKILL
  double interrupt_after = -1;  // > 0: SIGINT after this many seconds, as Ctrl-C would
  std::string stdout_path;      // instead of capturing stdout (e.g. /dev/full)
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
