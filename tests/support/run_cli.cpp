#include "support/run_cli.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
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

// The state letter and parent of process `pid` from /proc/PID/stat ("R", "T", "Z"…), or "" if gone.
struct ProcessState {
  std::string state;
  pid_t parent = 0;
  std::string name;
};
ProcessState process_state(pid_t pid) {
  const std::string stat = read_text("/proc/" + std::to_string(pid) + "/stat");
  const std::size_t name_end = stat.rfind(')');
  if (name_end == std::string::npos) return {};
  ProcessState p;
  p.name = stat.substr(stat.find('(') + 1, name_end - stat.find('(') - 1);
  std::istringstream rest(stat.substr(name_end + 1));
  rest >> p.state >> p.parent;
  return p;
}

// A python3 process descended from `program` (the chart drawer: its child, or a shell's between
// them) once it runs the interpreter, else 0.
pid_t find_drawer(pid_t program) {
  std::map<pid_t, ProcessState> processes;
  for (const fs::directory_entry& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(name));
    processes[pid] = process_state(pid);
  }
  for (const auto& [pid, p] : processes) {
    if (p.name.rfind("python3", 0) != 0) continue;
    pid_t parent = p.parent;
    for (int level = 0; level < 4 && parent != 0; ++level) {
      if (parent == program) return pid;
      parent = processes.count(parent) ? processes[parent].parent : 0;
    }
  }
  return 0;
}

// Freezes the drawer and sends the stop the options ask for; false while there is no drawer yet.
bool stop_while_drawing(pid_t program, pid_t& drawer, const RunOptions& options) {
  drawer = find_drawer(program);
  if (drawer == 0) return false;
  kill(drawer, SIGSTOP);
  for (int k = 0; k < 1000 && process_state(drawer).state != "T"; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (options.signal_while_drawing != 0) {
    kill(options.to_process_group ? -program : program, options.signal_while_drawing);
  }
  return true;
}

// After the program has ended: whether the drawer outlived it; continues it and waits (up to 30 s)
// until it has ended too.
bool outlived(pid_t drawer) {
  const std::string state = process_state(drawer).state;
  if (state.empty() || state == "Z" || state == "X") return false;
  kill(drawer, SIGCONT);
  for (int k = 0; k < 3000; ++k) {
    const std::string now = process_state(drawer).state;
    if (now.empty() || now == "Z" || now == "X") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

// posix_spawn with RLIMIT_FSIZE lowered meanwhile (the child inherits it, and SIGXFSZ ignored).
int spawn(pid_t& pid, char* const argv[], const posix_spawn_file_actions_t& files, const posix_spawnattr_t& attributes,
          long max_file_bytes) {
  rlimit previous{};
  getrlimit(RLIMIT_FSIZE, &previous);
  struct sigaction ignore {}, previous_action {};
  ignore.sa_handler = SIG_IGN;
  if (max_file_bytes > 0) {
    rlimit lowered = previous;
    lowered.rlim_cur = static_cast<rlim_t>(max_file_bytes);
    setrlimit(RLIMIT_FSIZE, &lowered);
    sigaction(SIGXFSZ, &ignore, &previous_action);
  }
  const int spawned = posix_spawn(&pid, BLADESTAB_EXE, &files, &attributes, argv, environ);
  if (max_file_bytes > 0) {
    setrlimit(RLIMIT_FSIZE, &previous);
    sigaction(SIGXFSZ, &previous_action, nullptr);
  }
  return spawned;
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
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  if (options.to_process_group) {  // its own group, so the test's own process is not signalled
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
  }
  pid_t pid = 0;
  const auto start = std::chrono::steady_clock::now();
  const int spawned = spawn(pid, argv.data(), files, attributes, options.max_file_bytes);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attributes);
  REQUIRE(spawned == 0);
  // Poll: a crash, an exit and a hang are all told apart by waitpid.
  bool interrupted = false;
  pid_t drawer = 0;
  while (true) {
    const pid_t done = waitpid(pid, &o.wait_status, WNOHANG);
    REQUIRE(done != -1);
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) break;
    if (options.interrupt_after > 0 && o.seconds > options.interrupt_after && !interrupted) {
      kill(pid, SIGINT);
      interrupted = true;
    }
    if (options.freeze_drawer && !o.drawer_seen) o.drawer_seen = stop_while_drawing(pid, drawer, options);
    if (o.seconds > options.timeout_seconds) {
      kill(pid, SIGKILL);
      waitpid(pid, &o.wait_status, 0);
      o.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (o.drawer_seen) o.drawer_outlived = outlived(drawer);
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
