#include "chart.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "chart_script.hpp"
#include "options.hpp"
#include "output_files.hpp"

namespace bladestab::cli {

namespace {
// Debian's interpreter: it has python3-matplotlib, whatever python3 comes first on PATH.
constexpr const char* python = "/usr/bin/python3";

// Writes all of `text` to `fd`; false if the reader went away. SIGPIPE is blocked meanwhile on
// this thread and a pending one taken, so a reader that died makes a failed write, not our death.
bool write_all(int fd, const std::string& text) {
  sigset_t pipe_signal, previous;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  bool written = true;
  for (std::size_t done = 0; done < text.size() && written;) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    written = n > 0;
    if (written) done += static_cast<std::size_t>(n);
  }
  const timespec now{0, 0};
  while (sigtimedwait(&pipe_signal, nullptr, &now) == SIGPIPE) {
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return written;
}

std::string read_all(int fd) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

// The last non-empty line of the script's stderr, without its "charts.py: " prefix: the script's
// own one-line error, or the last line of a Python traceback (e.g. a missing matplotlib).
std::string last_line(const std::string& text) {
  const std::size_t end = text.find_last_not_of('\n');
  if (end == std::string::npos) return "";
  const std::size_t newline = text.rfind('\n', end), start = newline == std::string::npos ? 0 : newline + 1;
  const std::string line = text.substr(start, end + 1 - start), prefix = "charts.py: ";
  return line.compare(0, prefix.size(), prefix) == 0 ? line.substr(prefix.size()) : line;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); !from.empty() && at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// What the script said on stderr and how it ended.
struct ScriptRun {
  int status = 0;  // waitpid's
  std::string errors;
};

// Runs the chart script (piped to the interpreter's stdin) with `arguments`, its stderr captured:
// the interpreter reads the whole script before it runs any of it, so the script is written in
// full before its stderr is read.
ScriptRun run_script(const std::vector<std::string>& arguments) {
  int input[2], errors[2];
  if (::pipe2(input, O_CLOEXEC) != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", python, std::strerror(errno)));
  if (::pipe2(errors, O_CLOEXEC) != 0) {
    ::close(input[0]), ::close(input[1]);
    throw std::runtime_error(fmt::format("cannot start {}: {}", python, std::strerror(errno)));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, input[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, errors[1], STDERR_FILENO);
  std::vector<std::string> words{python, "-"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, python, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(input[0]), ::close(errors[1]);
  ScriptRun run;
  if (spawned == 0) {
    write_all(input[1], chart_script);  // a script that stops early says why on stderr
    ::close(input[1]);
    run.errors = read_all(errors[0]);
    while (::waitpid(pid, &run.status, 0) < 0 && errno == EINTR) {
    }
  } else {
    ::close(input[1]);
  }
  ::close(errors[0]);
  if (spawned != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", python, std::strerror(spawned)));
  return run;
}
}  // namespace

void draw_chart(const std::string& kind, const std::string& json_path, const std::string& output_path,
                const std::string& shown_path) {
  const ScriptRun run = run_script({kind, json_path, output_path});
  if (WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) return;
  // One line with the cause: the script's (a full disk: "cannot write …: No space left on device"),
  // naming the file the user asked for, not its temporary.
  const std::string cause = replaced(replaced(last_line(run.errors), output_path, shown_path), json_path,
                                     shown_path + " (its data)");
  if (cause.find("No module named") != std::string::npos) {
    throw std::runtime_error(fmt::format("drawing {} failed: {} ({} with python3-matplotlib is needed)", shown_path,
                                         cause, python));
  }
  throw std::runtime_error(fmt::format("drawing {} failed: {}", shown_path,
                                       !cause.empty()            ? cause
                                       : WIFSIGNALED(run.status) ? fmt::format("{} ended by signal {}", python,
                                                                               WTERMSIG(run.status))
                                                                 : fmt::format("{} exited with status {}", python,
                                                                               WEXITSTATUS(run.status))));
}

void add_chart_options(CLI::App& command, std::string& out, std::string& chart, const std::string& out_help) {
  command.add_option("--out", out, out_help + " (default .)");
  command.add_option("--chart", chart, "chart format: png (default), svg or none")
      ->check(CLI::IsMember({"png", "svg", "none"}));
}

std::vector<std::string> write_outputs(const std::string& dir, const std::string& stem,
                                       const std::vector<std::pair<std::string, std::string>>& data,
                                       const std::string& json, const std::string& chart_kind,
                                       const std::string& chart_format) {
  const std::filesystem::path folder(dir);
  OutputFiles output;
  for (const auto& [name, text] : data) output.write((folder / name).string(), text);
  const std::string json_temporary = output.write((folder / (stem + ".json")).string(), json);
  if (chart_format != "none") {
    // Drawn from the JSON's temporary into its own: a failed drawing leaves no files at all.
    const std::string chart = (folder / (stem + "." + chart_format)).string();
    draw_chart(chart_kind, json_temporary, output.reserve(chart), chart);
  }
  return output.commit();
}

}  // namespace bladestab::cli
