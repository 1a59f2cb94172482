#include "support/run_cli.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <catch2/catch.hpp>

extern char** environ;

namespace testing_support {
namespace fs = std::filesystem;

const fs::path& scratch() {
  struct Dir {
    fs::path path;
    Dir() {
      std::string pattern = (fs::temp_directory_path() / "bladestab_cli_XXXXXX").string();
      if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed for " + pattern);
      path = pattern;
    }
    ~Dir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

namespace {

std::string shell_quote(const std::string& word) {
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

Outcome run_bladestab(const std::vector<std::string>& args, const RunOptions& options) {
  static int runs = 0;
  ++runs;
  const fs::path out = options.stdout_path.empty() ? scratch() / ("stdout_" + std::to_string(runs))
                                                   : fs::path(options.stdout_path);
  const fs::path err = scratch() / ("stderr_" + std::to_string(runs));
  Outcome o;
  o.command = shell_quote(BLADESTAB_EXE);
  for (const std::string& a : args) o.command += " " + shell_quote(a);

  std::vector<std::string> words{BLADESTAB_EXE};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const auto start = std::chrono::steady_clock::now();
  const int spawned = posix_spawn(&pid, BLADESTAB_EXE, &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  REQUIRE(spawned == 0);
  // Poll: a crash, an exit and a hang are all told apart by waitpid.
  bool interrupted = false;
  while (true) {
    const pid_t done = waitpid(pid, &o.wait_status, WNOHANG);
    REQUIRE(done != -1);
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) break;
    if (options.interrupt_after > 0 && o.seconds > options.interrupt_after && !interrupted) {
      kill(pid, SIGINT);
      interrupted = true;
    }
    if (o.seconds > options.timeout_seconds) {
      kill(pid, SIGKILL);
      waitpid(pid, &o.wait_status, 0);
      o.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  o.out = options.stdout_path.empty() ? read_text(out) : "";
  o.err = read_text(err);
  return o;
}

std::string describe(const Outcome& o) {
  if (o.timed_out) return "timed out after " + std::to_string(o.seconds) + " s";
  if (WIFEXITED(o.wait_status)) return "exit status " + std::to_string(WEXITSTATUS(o.wait_status));
  if (WIFSIGNALED(o.wait_status)) return "killed by signal " + std::to_string(WTERMSIG(o.wait_status));
  return "wait status " + std::to_string(o.wait_status);
}

Outcome expect_rejected(const std::vector<std::string>& args, const std::vector<std::string>& expected,
                        const RunOptions& options) {
  const Outcome o = run_bladestab(args, options);
  INFO("command: " << o.command);
  INFO("result:  " << describe(o));
  INFO("stdout:  " << o.out);
  INFO("stderr:  " << o.err);

  CHECK(!o.timed_out);
  CHECK(WIFEXITED(o.wait_status));
  CHECK(WEXITSTATUS(o.wait_status) == 2);
  CHECK(o.out.empty());
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
  CHECK((!o.err.empty() && o.err.back() == '\n'));
  CHECK_THAT(o.err, Catch::Matchers::StartsWith("bladestab: error: "));
  for (const std::string& entry : expected) {
    std::vector<std::string> options;
    std::istringstream split(entry);
    for (std::string option; std::getline(split, option, '|');) options.push_back(option);
    const bool found = std::any_of(options.begin(), options.end(),
                                   [&](const std::string& s) { return o.err.find(s) != std::string::npos; });
    INFO("expected the error line to contain: " << entry);
    CHECK(found);
  }
  return o;
}

}  // namespace testing_support
