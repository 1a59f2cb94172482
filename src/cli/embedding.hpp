#pragma once
// A command run inside another program (the Python module, python/): the same options, checks
// and JSON answer as on the command line, with the answer, the notes and the progress handed to
// the caller instead of stdout and stderr. The command runs on the calling thread; what it hands
// over goes to the EmbeddedRun of that thread, so runs on different threads stay apart.
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace bladestab::cli {

// A run past its --max-seconds, stopped at its next progress report (on the command line the
// program's watchdog stops it, interruption.hpp): "stopped at the time limit (--max-seconds 600): …".
class TimeLimitReached : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct EmbeddedRun {
  // Every progress report of the run, labelled as the command labels it, whatever the output
  // format. It may throw to stop the run: the exception leaves run_embedded as it is.
  std::function<void(const std::string& label, int done, int total)> progress;
  // The scene's TOML text; empty: the file the command's SCENE argument names (else that argument
  // is the scene's name in messages and outputs).
  std::string scene_text;
};

struct EmbeddedAnswer {
  std::string json;                // the answer's JSON document, as `--format json` prints it
  std::vector<std::string> notes;  // the lines the program prints as "bladestab: note: …"
  std::vector<std::string> files;  // the output files written (--out), the JSON document among them
  bool negative = false;           // complete but negative (`check`: a requirement not met)
  std::string negative_reason;     // its "failed" line, if it has one
};

// Runs `arguments` (the command, the scene and its options, as after `bladestab` on the command
// line). Bad input throws InputError with the program's one-line message naming the option or key;
// a failed check NumericalError or another exception, as the program reports them.
EmbeddedAnswer run_embedded(const std::vector<std::string>& arguments, const EmbeddedRun& run);

// Each command's long option names ("--tolerance", "--set", …), each with whether it takes a value
// (false for a flag such as "--help"), for callers that check options before running.
std::map<std::string, std::map<std::string, bool>> command_options();

// The answer's JSON document: into the current thread's embedded answer, else to stdout.
void print_json_answer(const std::string& text);

// The current thread's embedded run, or null on the command line; the answer it is collecting.
const EmbeddedRun* embedded_run();
EmbeddedAnswer* embedded_answer();

}  // namespace bladestab::cli
