// Stopping the program while it draws a chart (src/cli/interruption.hpp, src/cli/chart.cpp): the
// drawer, a python3 child, is frozen once it runs (tests/support/run_cli.hpp), so each stop lands
// mid-drawing on any machine. Whatever stops the run — SIGINT or SIGTERM to the program, Ctrl-C to
// its process group, the --max-seconds deadline — the drawer must not outlive the program, stderr
// must hold exactly the program's one line, the exit status must be the stop's, and --out must hold
// no file (no temporary either).
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "support/run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using testing_support::describe;
using testing_support::Outcome;
using testing_support::RunOptions;
using testing_support::run_bladestab;
using testing_support::scratch;

const std::string scene = BLADESTAB_SOURCE_DIR "/stability_maps/sinha2005/blade.toml";

// A small run of `command` that draws its chart into the directory `out`.
std::vector<std::string> drawing(const std::string& command, const fs::path& out) {
  std::vector<std::string> args{command, scene, "--set", "model.terms=4", "--out", out.string()};
  if (command == "sweep") args.insert(args.end(), {"--key", "operation.speed_rad_s", "--values", "0:300:3"});
  if (command == "campbell") args.insert(args.end(), {"--speeds", "0:600:3"});
  if (command == "map") {
    args.insert(args.end(), {"--plane", "theta-fmax", "--theta", "100:1000:3", "--fmax", "0:5:3", "--trace", "5",
                             "--resolution", "4x4"});
  }
  if (command == "transient") args.insert(args.end(), {"--revolutions", "0.5"});
  return args;
}

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

// The contract of a stop: `status`, one line on stderr containing `says`, nothing in `out`, no drawer left.
void expect_stopped(const Outcome& o, const fs::path& out, int status, const std::string& says) {
  INFO(o.command << "\n" << describe(o) << "\nstderr: " << o.err);
  REQUIRE(o.drawer_seen);
  CHECK(!o.drawer_outlived);
  CHECK((WIFEXITED(o.wait_status) && WEXITSTATUS(o.wait_status) == status));
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
  CHECK(o.err.find(says) != std::string::npos);
  CHECK(o.err.find("Traceback") == std::string::npos);
  const std::vector<std::string> left = files_in(out);
  INFO("left in --out: " << left.size() << (left.empty() ? "" : ", the first " + left.front()));
  CHECK(left.empty());
}

}  // namespace

TEST_CASE("interruption: a signal while a chart is drawn ends the drawer, one line, no files", "[interruption][parallel][long_under_sanitizers]") {
  RunOptions options;
  options.freeze_drawer = true;
  options.timeout_seconds = 120;
  SECTION("SIGINT to the program while sweep draws") {
    options.signal_while_drawing = SIGINT;
    const fs::path out = scratch() / "stopped_sweep";
    expect_stopped(run_bladestab(drawing("sweep", out), options), out, 130, "interrupted (SIGINT)");
  }
  SECTION("Ctrl-C to the process group while campbell draws: the drawer ignores it, the program ends it") {
    options.signal_while_drawing = SIGINT;
    options.to_process_group = true;
    const fs::path out = scratch() / "stopped_campbell";
    expect_stopped(run_bladestab(drawing("campbell", out), options), out, 130, "interrupted (SIGINT)");
  }
  SECTION("SIGTERM to the process group while map draws") {
    options.signal_while_drawing = SIGTERM;
    options.to_process_group = true;
    const fs::path out = scratch() / "stopped_map";
    expect_stopped(run_bladestab(drawing("map", out), options), out, 143, "terminated (SIGTERM)");
  }
}

TEST_CASE("interruption: the time limit while a chart is drawn ends the drawer, one line, no files",
          "[interruption][parallel]") {
  RunOptions options;
  options.freeze_drawer = true;  // and no signal: the drawer never ends by itself
  options.timeout_seconds = 120;
  const fs::path out = scratch() / "stopped_transient";
  std::vector<std::string> args = drawing("transient", out);
  // 5 s of wall time, little CPU: the transient itself takes 0.07 s here, well under 1 s in a
  // sanitizer build on a loaded machine, so the deadline comes while the drawer is frozen.
  args.insert(args.end(), {"--max-seconds", "5"});
  expect_stopped(run_bladestab(args, options), out, 1, "stopped at the time limit (--max-seconds 5)");
}

TEST_CASE("outputs: a chart that cannot be written is refused as every output file is: one line, no files",
          "[interruption][parallel]") {
  // A limit on the size of the files the program writes (RLIMIT_FSIZE) a little above the largest
  // it writes itself (the chart script, joined from scripts/charts/, into memory for the drawer) and below the chart (90 kB
  // against the script's 54 kB when written): the drawer's write fails as on a full disk (EFBIG
  // here, ENOSPC there: the same failed write). A chart that fits would exit 0 and fail the test.
  RunOptions options;
  long script_bytes = 0;  // the joined script is the modules less their imports of each other
  for (const auto& module : fs::directory_iterator(BLADESTAB_SOURCE_DIR "/scripts/charts")) {
    if (module.path().extension() == ".py") script_bytes += static_cast<long>(module.file_size());
  }
  options.max_file_bytes = script_bytes + 8192;
  const fs::path out = scratch() / "chart_too_big";
  const Outcome o = run_bladestab(drawing("sweep", out), options);
  INFO(o.command << "\n" << describe(o) << "\nstderr: " << o.err);
  CHECK((WIFEXITED(o.wait_status) && WEXITSTATUS(o.wait_status) == 2));
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
  const std::string chart = (out / "sweep.png").string();
  CHECK(o.err == "bladestab: error: " + chart + ": cannot write this file: File too large\n");
  CHECK(o.err.find("matplotlib") == std::string::npos);
  CHECK(files_in(out).empty());
}

TEST_CASE("outputs: a stderr that cannot take the whole line still ends the run with its status",
          "[interruption]") {
  // The same limit on stderr's file as on the outputs (60 bytes): the output file fails, and the
  // one line about it is cut at the limit; the run exits 2 as it would with the whole line.
  RunOptions options;
  options.max_file_bytes = 60;
  const fs::path out = scratch() / "stderr_too_small";
  std::vector<std::string> args = drawing("transient", out);
  args.insert(args.end(), {"--chart", "none"});
  const Outcome o = run_bladestab(args, options);
  INFO(o.command << "\n" << describe(o) << "\nstderr: " << o.err);
  CHECK((WIFEXITED(o.wait_status) && WEXITSTATUS(o.wait_status) == 2));
  CHECK(o.err == std::string("bladestab: error: " + (out / "transient.csv").string() + ": cannot write this file")
                     .substr(0, 60));
  CHECK(files_in(out).empty());
}

namespace {

// Everything the program writes to stderr when stderr is a terminal (a pseudo-terminal here; stdout
// goes to /dev/null): its progress line and its last line. SIGINT goes to the program once its
// stderr holds `interrupt_after`.
std::string terminal_stderr(const std::vector<std::string>& args, const std::string& interrupt_after) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  REQUIRE(master >= 0);
  REQUIRE(grantpt(master) == 0);
  REQUIRE(unlockpt(master) == 0);
  const std::string slave = ptsname(master);
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const int tty = open(slave.c_str(), O_RDWR), null = open("/dev/null", O_WRONLY);
    dup2(null, STDOUT_FILENO);
    dup2(tty, STDERR_FILENO);
    std::vector<char*> argv{const_cast<char*>(BLADESTAB_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(BLADESTAB_EXE, argv.data());
    _exit(127);
  }
  std::string text;
  char buffer[4096];
  bool interrupted = false;
  for (ssize_t n; (n = read(master, buffer, sizeof buffer)) > 0;) {
    text.append(buffer, static_cast<std::size_t>(n));
    if (!interrupted && text.find(interrupt_after) != std::string::npos) interrupted = kill(pid, SIGINT) == 0;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  close(master);
  return text;
}

}  // namespace

TEST_CASE("a run stopped mid-progress on a terminal writes its line over the progress line, not after it",
          "[interruption]") {
  // Ctrl-C while "campbell: speeds k/20000" stands: the stop's line had followed it on the same
  // line ("… ( 7%)bladestab: stopped: …").
  const std::string text = terminal_stderr({"campbell", scene, "--speeds", "0:400:20000", "--chart", "none", "--out",
                                            (scratch() / "terminal_progress").string()},
                                           "campbell: speeds");
  const std::size_t line = text.find("bladestab: stopped: interrupted (SIGINT)");
  INFO(text.substr(text.size() > 300 ? text.size() - 300 : 0));
  REQUIRE(line != std::string::npos);
  REQUIRE(text.rfind("campbell: speeds", line) != std::string::npos);  // the progress stood there
  CHECK(text[line - 1] == '\r');
}
