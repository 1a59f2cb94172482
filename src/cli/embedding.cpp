#include "embedding.hpp"

#include <algorithm>
#include <chrono>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

struct ThreadRun {
  const EmbeddedRun* run = nullptr;
  EmbeddedAnswer* answer = nullptr;
};
thread_local ThreadRun current;

// Installs a run on this thread for its lifetime.
class CurrentRun {
public:
  CurrentRun(const EmbeddedRun& run, EmbeddedAnswer& answer) : saved_(current) { current = {&run, &answer}; }
  ~CurrentRun() { current = saved_; }
  CurrentRun(const CurrentRun&) = delete;
  CurrentRun& operator=(const CurrentRun&) = delete;

private:
  ThreadRun saved_;
};

// The run with its progress reports checking the time limit first.
EmbeddedRun with_deadline(const EmbeddedRun& run, double seconds) {
  using clock = std::chrono::steady_clock;
  const clock::time_point deadline = clock::now() + std::chrono::duration_cast<clock::duration>(
                                                        std::chrono::duration<double>(std::min(seconds, 1e9)));
  EmbeddedRun checked = run;
  checked.progress = [progress = run.progress, deadline, seconds](const std::string& label, int done, int total) {
    if (clock::now() > deadline) {
      throw TimeLimitReached(fmt::format("stopped at the time limit (--max-seconds {:g}): the run took longer than "
                                         "estimated", seconds));
    }
    if (progress) progress(label, done, total);
  };
  return checked;
}

}  // namespace

const EmbeddedRun* embedded_run() { return current.run; }
EmbeddedAnswer* embedded_answer() { return current.answer; }

void print_json_answer(const std::string& text) {
  if (current.answer != nullptr) {
    current.answer->json = text;
  } else {
    fmt::print("{}", text);
  }
}

EmbeddedAnswer run_embedded(const std::vector<std::string>& arguments, const EmbeddedRun& run) {
  work_limits() = WorkLimits{};  // the options below bind to this thread's limits and set what is given
  CLI::App app{"bladestab"};
  const std::map<std::string, Command> commands = register_commands(app);
  check_command_name(commands, arguments.empty() ? nullptr : arguments.front().c_str());
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {  // --help among them: there is no help to print here
    throw InputError(parse_error_text(e));
  }
  EmbeddedAnswer answer;
  const EmbeddedRun checked = with_deadline(run, work_limits().seconds);
  const CurrentRun installed(checked, answer);
  try {
    commands.at(app.get_subcommands().front()->get_name())();
  } catch (const AnswerIsNegative& e) {
    answer.negative = true;
    answer.negative_reason = e.reason;
  } catch (const ParameterError& e) {  // the library's parameter is the command's option
    throw InputError("--" + std::string(e.what()));
  }
  return answer;
}

std::map<std::string, std::map<std::string, bool>> command_options() {
  CLI::App app{"bladestab"};
  std::map<std::string, std::map<std::string, bool>> names;
  for (const auto& [name, unused] : register_commands(app)) {
    for (const CLI::Option* option : app.get_subcommand(name)->get_options()) {
      const bool takes_value = option->get_items_expected_max() > 0;
      for (const std::string& long_name : option->get_lnames()) names[name]["--" + long_name] = takes_value;
    }
  }
  return names;
}

}  // namespace bladestab::cli
