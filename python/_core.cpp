// bladestab._core: the program's commands run in this process (src/cli/embedding.hpp), for the
// Python package beside it (python/bladestab/). The command runs with the GIL released; its
// progress reports come back here, where Ctrl-C (Python's pending signals, on the thread that
// started the run) and the caller's callback may stop it.
#include <signal.h>

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bladestab/base/input_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "embedding.hpp"
#include "support/blas_threads.hpp"

namespace py = pybind11;

namespace {

// Ctrl-C while a run computes. Python's own handler only marks the signal for the main thread's
// next PyErr_CheckSignals, which a run's other threads cannot call; so while a run started on the
// main thread computes, this handler counts the signal for every thread of the run and then hands
// it on to Python's, which raises KeyboardInterrupt when the run has unwound. Only where SIGINT's
// Python handler is Python's default (KeyboardInterrupt): a handler of the caller's own runs at the
// caller thread's progress reports and stops the run only if it raises, as in plain Python.
std::atomic<unsigned long> interrupts{0};
struct sigaction python_handler;
int watches = 0;  // the runs watching on the main thread (a run started in another's progress callback); GIL

extern "C" void note_interrupt(int signal_number) {
  interrupts.fetch_add(1);
  python_handler.sa_handler(signal_number);
}

// Whether Ctrl-C raises KeyboardInterrupt on this thread: the main thread, under Python's default handler.
bool default_interrupt_here() {
  const py::object threading = py::module_::import("threading");
  const py::object signal = py::module_::import("signal");
  return threading.attr("current_thread")().is(threading.attr("main_thread")()) &&
         signal.attr("getsignal")(SIGINT).is(signal.attr("default_int_handler"));
}

class InterruptWatch {
public:
  InterruptWatch() {
    if (!default_interrupt_here()) return;
    if (watches == 0 && !install()) return;
    ++watches;
    watching_ = true;
    start_ = interrupts.load();
  }
  ~InterruptWatch() {
    if (watching_ && --watches == 0) sigaction(SIGINT, &python_handler, nullptr);
  }
  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;

  // Whether Ctrl-C came since this run started; any thread.
  bool interrupted() const { return watching_ && interrupts.load() != start_; }

private:
  static bool install() {
    struct sigaction current;
    if (sigaction(SIGINT, nullptr, &current) != 0 || (current.sa_flags & SA_SIGINFO) != 0 ||
        current.sa_handler == SIG_DFL || current.sa_handler == SIG_IGN) {
      return false;  // no Python handler at the C level to hand the signal on to
    }
    python_handler = current;
    struct sigaction ours = current;
    ours.sa_handler = note_interrupt;
    return sigaction(SIGINT, &ours, nullptr) == 0;
  }

  bool watching_ = false;
  unsigned long start_ = 0;
};

// Thrown through the library to stop a run; it is no std::exception, so nothing on the way takes
// it for a failure of the analysis.
struct Stopped {};

// What stops a run: the first Python error raised in a progress report (KeyboardInterrupt or the
// callback's own), kept until the run has unwound.
class RunStop {
public:
  RunStop(py::object callback, const InterruptWatch& watch)
      : callback_(std::move(callback)), caller_(std::this_thread::get_id()), watch_(watch) {}

  // Called from the library, on any of its threads, without the GIL.
  void report(const std::string& label, int done, int total) {
    if (stopped_.load() || watch_.interrupted()) throw Stopped{};
    py::gil_scoped_acquire gil;
    try {
      // Signal handlers run only on the main thread; PyErr_CheckSignals elsewhere does nothing.
      if (std::this_thread::get_id() == caller_ && PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback_.is_none()) callback_(label, done, total);
    } catch (py::error_already_set& e) {
      if (!error_) error_ = std::move(e);
      stopped_.store(true);
      throw Stopped{};
    }
  }

  // After the run, with the GIL: the Python error that stopped it (KeyboardInterrupt from the
  // handler Ctrl-C was handed on to).
  [[noreturn]] void raise() {
    if (error_) throw std::move(*error_);
    // Python's default handler raises KeyboardInterrupt; a run inside this one's callback may have taken it.
    if (PyErr_CheckSignals() == 0) PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }

private:
  py::object callback_;
  std::thread::id caller_;
  const InterruptWatch& watch_;
  std::atomic<bool> stopped_{false};
  std::optional<py::error_already_set> error_;  // guarded by the GIL
};

py::dict answer_dict(const bladestab::cli::EmbeddedAnswer& answer) {
  py::dict d;
  d["json"] = answer.json;
  d["notes"] = answer.notes;
  d["files"] = answer.files;
  d["negative"] = answer.negative;
  d["negative_reason"] = answer.negative_reason;
  return d;
}

// run(arguments, scene_text="", progress=None) -> {"json", "notes", "files", "negative",
// "negative_reason"}; the arguments as after `bladestab` on the command line.
py::dict run(const std::vector<std::string>& arguments, const std::string& scene_text, py::object progress) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr())) {
    throw bladestab::InputError("progress: must be callable as progress(label, done, total), or None");
  }
  const InterruptWatch watch;
  auto stop = std::make_shared<RunStop>(std::move(progress), watch);
  bladestab::cli::EmbeddedRun request;
  request.scene_text = scene_text;
  RunStop* reports = stop.get();
  request.progress = [reports](const std::string& label, int done, int total) { reports->report(label, done, total); };
  std::optional<bladestab::cli::EmbeddedAnswer> answer;
  bool stopped = false;
  {
    py::gil_scoped_release released;
    try {
      answer = bladestab::cli::run_embedded(arguments, request);
    } catch (const Stopped&) {
      stopped = true;
    }
  }
  if (stopped) stop->raise();
  return answer_dict(*answer);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "bladestab's commands run in this process; the package bladestab wraps them";
  bladestab::use_single_threaded_blas();
  py::register_exception<bladestab::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<bladestab::NumericalError>(m, "NumericalError", PyExc_RuntimeError);
  py::register_exception<bladestab::cli::TimeLimitReached>(m, "TimeLimitReached", PyExc_TimeoutError);
  m.def("run", &run, py::arg("arguments"), py::arg("scene_text") = "", py::arg("progress") = py::none(),
        "Runs one command in this process: the arguments as after `bladestab` on the command line.");
  m.def("command_options", &bladestab::cli::command_options, "Each command's long option names, each with whether it takes a value.");
}
