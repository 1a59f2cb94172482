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
// main thread computes, this handler notes the signal for every thread and then hands it on to
// Python's, which raises KeyboardInterrupt when the run has unwound.
std::atomic<bool> interrupted{false};
struct sigaction python_handler;

extern "C" void note_interrupt(int signal_number) {
  interrupted.store(true);
  python_handler.sa_handler(signal_number);
}

class InterruptWatch {
public:
  InterruptWatch() {
    struct sigaction current;
    const py::object threading = py::module_::import("threading");
    if (!threading.attr("current_thread")().is(threading.attr("main_thread")()) ||
        sigaction(SIGINT, nullptr, &current) != 0 || (current.sa_flags & SA_SIGINFO) != 0 ||
        current.sa_handler == SIG_DFL || current.sa_handler == SIG_IGN) {
      return;  // not the main thread, or no Python handler to hand the signal on to
    }
    python_handler = current;
    struct sigaction ours = current;
    ours.sa_handler = note_interrupt;
    interrupted.store(false);
    watching_ = sigaction(SIGINT, &ours, nullptr) == 0;
  }
  ~InterruptWatch() {
    if (watching_) sigaction(SIGINT, &python_handler, nullptr);
  }
  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;

private:
  bool watching_ = false;
};

// Thrown through the library to stop a run; it is no std::exception, so nothing on the way takes
// it for a failure of the analysis.
struct Stopped {};

// What stops a run: the first Python error raised in a progress report (KeyboardInterrupt or the
// callback's own), kept until the run has unwound.
class RunStop {
public:
  RunStop(py::object callback) : callback_(std::move(callback)), caller_(std::this_thread::get_id()) {}

  // Called from the library, on any of its threads, without the GIL.
  void report(const std::string& label, int done, int total) {
    if (stopped_.load() || interrupted.load()) throw Stopped{};
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
    if (PyErr_CheckSignals() == 0) PyErr_SetNone(PyExc_KeyboardInterrupt);  // a handler that did not raise
    throw py::error_already_set();
  }

private:
  py::object callback_;
  std::thread::id caller_;
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
  auto stop = std::make_shared<RunStop>(std::move(progress));
  bladestab::cli::EmbeddedRun request;
  request.scene_text = scene_text;
  RunStop* reports = stop.get();
  request.progress = [reports](const std::string& label, int done, int total) { reports->report(label, done, total); };
  std::optional<bladestab::cli::EmbeddedAnswer> answer;
  bool stopped = false;
  {
    const InterruptWatch watch;
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
  m.def("command_options", &bladestab::cli::command_options, "Each command's long option names.");
}
