#include "chart.hpp"

#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "chart_script.hpp"
#include "embedding.hpp"
#include "interruption.hpp"
#include "options.hpp"
#include "output_files.hpp"
#include "support/message_text.hpp"

namespace bladestab::cli {

namespace {
// Debian's interpreter: it has python3-matplotlib, whatever python3 comes first on PATH.
constexpr const char* python = "/usr/bin/python3";

// An anonymous file in memory: the script the interpreter reads, and what it says. Neither needs
// a pipe (a drawer that dies early cannot SIGPIPE the program) nor room on any disk.
int memory_file(const char* name, const std::string& text) {
  const int fd = ::memfd_create(name, MFD_CLOEXEC);
  if (fd < 0) throw std::runtime_error(fmt::format("cannot draw the chart: memfd_create: {}", std::strerror(errno)));
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n <= 0) {
      ::close(fd);
      throw std::runtime_error(fmt::format("cannot draw the chart: {}", std::strerror(errno)));
    }
    done += static_cast<std::size_t>(n);
  }
  ::lseek(fd, 0, SEEK_SET);
  return fd;
}

std::string read_all(int fd) {
  std::string text;
  ::lseek(fd, 0, SEEK_SET);
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
  return text;
}

// The child, between fork and exec (async-signal-safe calls only): SIGINT and SIGTERM ignored, so
// Ctrl-C on the terminal's process group reaches the program alone, which ends the drawer itself
// (interruption.hpp); SIGKILL when the program ends by any other means; the script on stdin and
// everything the interpreter prints into `messages`.
[[noreturn]] void become_drawer(pid_t program, int script, int messages, char* const argv[]) {
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGINT, &ignore, nullptr);
  ::sigaction(SIGTERM, &ignore, nullptr);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != program) ::_exit(127);  // the program ended before the line above
  if (::dup2(script, STDIN_FILENO) < 0 || ::dup2(messages, STDOUT_FILENO) < 0 || ::dup2(messages, STDERR_FILENO) < 0) {
    ::_exit(127);
  }
  ::execv(python, argv);
  ::_exit(127);
}

// Starts the drawer, known to interruption.hpp before any stop can see it.
pid_t start_drawer(int script, int messages, std::vector<std::string> words) {
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t program = ::getpid();
  const StopDeferral deferral;
  const pid_t pid = ::fork();
  if (pid == 0) become_drawer(program, script, messages, argv.data());
  if (pid < 0) throw std::runtime_error(fmt::format("cannot start {}: {}", python, std::strerror(errno)));
  remember_child(pid);
  return pid;
}

// Waits for the drawer to end, then forgets and reaps it with stops deferred (interruption.hpp).
int wait_for_drawer(pid_t pid) {
  siginfo_t info;
  while (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOWAIT) != 0 && errno == EINTR) {
  }
  const StopDeferral deferral;
  forget_child();
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

// Why a drawing failed, in one line: the script's own message ("charts: …", without that) or
// the last line of the interpreter's traceback.
std::string drawing_failure(int status, std::string said) {
  while (!said.empty() && std::isspace(static_cast<unsigned char>(said.back()))) said.pop_back();
  std::string reason = said.substr(said.rfind('\n') + 1);  // from the start when there is one line
  if (reason.rfind("charts: ", 0) == 0) reason.erase(0, 8);
  if (WIFSIGNALED(status)) return fmt::format("{} ended by signal {}", python, WTERMSIG(status));
  if (WEXITSTATUS(status) == 127 || reason.empty()) return fmt::format("cannot run {} (with python3-matplotlib)", python);
  if (reason.find("No module named") != std::string::npos) {
    reason += fmt::format(" ({} with python3-matplotlib is needed)", python);
  }
  return reason;
}

// A file descriptor closed when it goes out of scope.
struct OpenFile {
  int fd;
  ~OpenFile() { ::close(fd); }
};

}  // namespace

void draw_chart(const std::string& kind, const std::string& json_path, const std::string& temporary,
                const std::string& output_path) {
  const OpenFile script{memory_file("charts.py", chart_script)};
  const OpenFile messages{memory_file("charts.py messages", "")};
  const int status = wait_for_drawer(start_drawer(script.fd, messages.fd, {python, "-", kind, json_path, temporary}));
  if (status == 0) return;
  std::string reason = drawing_failure(status, read_all(messages.fd));
  // A chart that cannot be written (a full disk) is refused as every output file is (output_files.hpp).
  const std::string unwritable = "cannot write '" + temporary + "': ";
  if (reason.rfind(unwritable, 0) == 0) {
    throw InputError(fmt::format("{}: cannot write this file: {}", echoed(output_path, 240), reason.substr(unwritable.size())));
  }
  for (std::size_t at; (at = reason.find(temporary)) != std::string::npos;) reason.replace(at, temporary.size(), output_path);
  throw std::runtime_error(fmt::format("drawing {} failed: {}", output_path, reason));
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
  std::vector<std::string> written = output.commit();
  if (EmbeddedAnswer* answer = embedded_answer(); answer != nullptr) answer->files = written;
  return written;
}

}  // namespace bladestab::cli
