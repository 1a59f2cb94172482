// bladestab: dynamic stability of rotating blades whose tips rub the casing.
//
// Exit status: 0 with the answer on stdout (1 where the answer is negative: `check` with a requirement
// not met); 2 for bad input (InputError: a scene key, an option, a
// limit of work), one line on stderr naming it; 1 when a computation fails its own checks
// (NumericalError) or anything else fails, also one line; 128 + n when stopped by signal n
// (interruption.hpp). Nothing non-finite is ever printed as an answer.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <new>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "support/blas_threads.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "commands.hpp"
#include "notes.hpp"
#include "options.hpp"
#include "interruption.hpp"
#include "work_limits.hpp"

namespace {

// "bladestab: error: …" (kind "error", exit 2) or "bladestab: failed: …" (exit 1), on one line
// (notes.hpp).
int report(const char* kind, const std::string& message, int status) {
  bladestab::cli::end_of_run();
  bladestab::cli::print_stderr_line(kind, message);
  return status;
}

// The answer went to stdout; a write that failed there (a full disk, /dev/full, a closed pipe
// with SIGPIPE ignored) is a failure of the run, not a success with a lost answer.
int finish_stdout() {
  bladestab::cli::end_of_run();
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    return report("failed", fmt::format("cannot write the output to stdout: {}", std::strerror(errno)), 1);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bladestab::cli;
  bladestab::use_single_threaded_blas();
  stop_on_signals();
  CLI::App app{"bladestab: modes, Campbell diagrams and dynamic stability of rotating Timoshenko blades"};
  const std::map<std::string, Command> run = register_commands(app);
  try {
    check_command_name(run, argc < 2 ? nullptr : argv[1]);
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return report("error", fmt::format("{} (see bladestab --help)", parse_error_text(e)), 2);
  } catch (const bladestab::InputError& e) {  // a number option's value (number_options.hpp)
    return report("error", e.what(), 2);
  }
  // The library names an analysis's parameter ("tolerance 1e-13: …"); here it is the option --tolerance.
  const auto as_option = [](const bladestab::ParameterError& e) { return "--" + std::string(e.what()); };
  stop_after(work_limits().seconds, fmt::format("--max-seconds {:g}", work_limits().seconds));
  try {
    run.at(app.get_subcommands().front()->get_name())();
  } catch (const AnswerIsNegative& e) {
    finish_stdout();  // a failed write says so; the status is 1 either way
    return e.reason.empty() ? 1 : report("failed", e.reason, 1);
  } catch (const bladestab::ParameterError& e) {
    return report("error", as_option(e), 2);
  } catch (const bladestab::InputError& e) {
    return report("error", e.what(), 2);
  } catch (const bladestab::WorkLimitError& e) {
    return report("failed", with_max_seconds(e.what()), 1);
  } catch (const std::bad_alloc&) {
    return report("failed", "out of memory", 1);
  } catch (const std::exception& e) {
    return report("failed", e.what(), 1);
  }
  return finish_stdout();
}
