#include "interruption.hpp"

#include <signal.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

#include <array>
#include <atomic>
#include <chrono>
#include <cstring>
#include <mutex>
#include <new>
#include <thread>

#include <fmt/format.h>

#include "progress.hpp"

namespace bladestab::cli {
namespace {

// The registry of temporaries is read by a signal handler, so it is plain memory: fixed slots,
// each claimed and published through lock-free atomics, its path a fixed buffer.
constexpr std::size_t slots = 64, max_path = 4096;
struct Slot {
  std::atomic<bool> claimed{false}, published{false};
  char path[max_path] = {};
};
std::array<Slot, slots> registry;

std::atomic<pid_t> child{0};

// Once a set of output files is in place, a stop says so rather than that none was written.
std::atomic<bool> files_written{false};
const char* files_note() {
  return files_written.load() ? "; its output files were written\n" : "; no output files written\n";
}

// async-signal-safe: kill, waitid and unlink only. The child is waited for without being reaped
// (WNOWAIT), so its process id stays its own while the main thread may wait for it too.
void end_child_and_remove_temporaries() {
  const pid_t pid = child.load();
  if (pid > 0) {
    ::kill(pid, SIGKILL);
    siginfo_t info;
    while (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOWAIT) != 0 && errno == EINTR) {
    }
  }
  for (Slot& s : registry) {
    if (s.published.load()) ::unlink(s.path);
  }
}

void write_line(const char* text) {  // async-signal-safe
  const std::size_t length = std::strlen(text);
  for (std::size_t done = 0; done < length;) {
    const ssize_t n = ::write(STDERR_FILENO, text + done, length - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
}

// The deadline takes this lock before it stops the run; a StopDeferral holds it meanwhile.
std::mutex& commit_lock() {
  static std::mutex lock;
  return lock;
}

// Ends the process at once, the run's threads with it, as glibc's _exit does (async-signal-safe).
// The system call itself, because a sanitizer's _exit first finalizes: it reports the stopped run's
// threads as leaked and sleeps while they go on computing.
[[noreturn]] void end_process(int status) {
  ::syscall(SYS_exit_group, status);
  __builtin_unreachable();
}

extern "C" void stop_on_signal(int signal_number) {
  end_child_and_remove_temporaries();
  clear_progress_line();
  write_line(signal_number == SIGINT ? "bladestab: stopped: interrupted (SIGINT)" : "bladestab: stopped: terminated (SIGTERM)");
  write_line(files_note());
  end_process(128 + signal_number);
}

sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

}  // namespace

void stop_on_signals() {
  struct sigaction action {};
  action.sa_handler = stop_on_signal;
  action.sa_mask = stop_signals();  // a second signal waits for the first's stop
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

void stop_after(double seconds, const std::string& limit) {
  const std::string message =
      fmt::format("bladestab: failed: stopped at the time limit ({}): the run took longer than estimated", limit);
  // The watchdog starts with SIGINT and SIGTERM blocked, so they never run on it while a set of
  // files is being renamed on the main thread.
  const sigset_t set = stop_signals();
  sigset_t previous;
  pthread_sigmask(SIG_BLOCK, &set, &previous);
  std::thread([seconds, message] {
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    commit_lock().lock();  // never released: the process ends here
    end_child_and_remove_temporaries();
    clear_progress_line();
    write_line(message.c_str());
    write_line(files_note());
    end_process(1);
  }).detach();
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

int remember_temporary(const std::string& path) {
  if (path.size() >= max_path) return -1;
  for (std::size_t k = 0; k < slots; ++k) {
    bool expected = false;
    if (!registry[k].claimed.compare_exchange_strong(expected, true)) continue;
    std::memcpy(registry[k].path, path.c_str(), path.size() + 1);
    registry[k].published.store(true);
    return static_cast<int>(k);
  }
  return -1;
}

void forget_temporary(int slot) {
  if (slot < 0) return;
  registry[slot].published.store(false);
  registry[slot].claimed.store(false);
}

void remember_child(pid_t pid) { child.store(pid); }

void forget_child() { child.store(0); }

void note_files_written() { files_written.store(true); }

// Signals are blocked (they stay pending and stop the run once the set is in place); the deadline
// waits for the lock.
StopDeferral::StopDeferral() {
  const sigset_t set = stop_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  commit_lock().lock();
}

StopDeferral::~StopDeferral() {
  commit_lock().unlock();
  const sigset_t set = stop_signals();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

void end_of_run() {
  // Built once in static storage and never destroyed: the deferral lasts until the process ends.
  alignas(StopDeferral) static unsigned char storage[sizeof(StopDeferral)];
  static const StopDeferral* const held = new (storage) StopDeferral;
  static_cast<void>(held);
}

}  // namespace bladestab::cli
