#pragma once
// Independent tasks run side by side: the one way the library runs work in parallel (the map's
// points, the sweep's values, the boundaries' two multiplier signs, the error budget's variants,
// the Campbell estimate's richer models).
//
// WorkPool runs task(0) … task(count − 1) on up to `threads` threads, the caller's included:
// threads − 1 helper threads take the tasks in index order from the moment the pool is made, and
// whatever no helper has started when the caller asks for a result runs on the caller's thread.
// So the caller can do its own work meanwhile, never idles while tasks wait, and no more than
// `threads` run at once; with one thread every task runs in turn on the caller, when asked for.
// Results come back by index, so an answer never depends on the thread count.
//
// A task that throws cancels the tasks after it that have not started (those before it all run,
// as they would one at a time), and the exception of the lowest index that failed is rethrown —
// the one a run on one thread reports: get(i) waits for tasks 0 … i and rethrows the lowest
// failure among them, in whatever order the results are asked for. Long tasks may poll a
// Cancellation: it is set once a task has failed and every task before it has ended, or by whoever
// holds it (a task that stops for it throws WorkCancelled). A task that throws WorkCancelled, for
// this pool's flag or one of its own, keeps the tasks after it from starting.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace bladestab {

// How many threads an analysis may run at once: `requested`, or one per core for 0.
int worker_threads(int requested);

// A flag the tasks of a pool may poll to stop early; shared with the pool that sets it.
class Cancellation {
public:
  void cancel() { cancelled_ = true; }
  bool cancelled() const { return cancelled_; }

private:
  std::atomic<bool> cancelled_{false};
};

// Thrown for a task that did not run because the run was cancelled from outside (or that stopped
// for its Cancellation).
class WorkCancelled : public std::runtime_error {
public:
  WorkCancelled() : std::runtime_error("the work was cancelled") {}
};

// The pool without its results: claims tasks in index order, runs them on the helpers and the
// caller, records how each ended.
class TaskRunner {
public:
  TaskRunner(int threads, std::size_t count, std::function<void(std::size_t)> run, Cancellation* cancellation);
  TaskRunner(const TaskRunner&) = delete;
  TaskRunner& operator=(const TaskRunner&) = delete;
  // No unstarted task starts any more; the running ones finish.
  ~TaskRunner();

  // Runs the unstarted tasks on the caller, then waits for tasks 0 … i; rethrows the exception of
  // the lowest of them that failed, or, for a task i that was cancelled, the exception that
  // cancelled it.
  void wait_for(std::size_t i);
  // The same for every task; the exception of the lowest index rethrown.
  void wait_all();

private:
  enum class End { pending, done, failed, skipped };
  void run_unstarted();
  void cancel_after_failure();
  [[noreturn]] void rethrow_first(std::unique_lock<std::mutex>& lock);

  std::size_t count_;
  std::function<void(std::size_t)> run_;
  Cancellation own_;
  Cancellation* cancellation_;
  std::atomic<std::size_t> next_{0}, first_failure_;
  std::atomic<bool> stopped_{false};  // a task threw WorkCancelled
  std::mutex lock_;
  std::condition_variable settled_;
  std::vector<End> end_;
  std::vector<std::exception_ptr> failure_;
  std::size_t settled_count_ = 0;
  std::vector<std::thread> helpers_;
};

template <class Result>
class WorkPool {
public:
  // Starts the tasks; `cancellation` (optional) is the flag the tasks poll, else the pool's own.
  WorkPool(int threads, std::size_t count, std::function<Result(std::size_t)> task,
           Cancellation* cancellation = nullptr)
      : task_(std::move(task)),
        results_(count),
        runner_(threads, count, [this](std::size_t i) { results_[i].emplace(task_(i)); }, cancellation) {}

  // Task i's result (at most once per task), or the lowest failure among tasks 0 … i (wait_for).
  Result get(std::size_t i) {
    runner_.wait_for(i);
    return std::move(*results_[i]);
  }
  // Every result in index order.
  std::vector<Result> results() {
    runner_.wait_all();
    std::vector<Result> out;
    out.reserve(results_.size());
    for (std::optional<Result>& r : results_) out.push_back(std::move(*r));
    return out;
  }

private:
  std::function<Result(std::size_t)> task_;
  std::vector<std::optional<Result>> results_;
  TaskRunner runner_;  // last: its threads stop before the results go
};

// task(i) for i = 0 … count − 1 on up to `threads` threads; their results in index order (none
// for a task that returns nothing).
template <class Task>
auto run_indexed(std::size_t count, int threads, Task task) {
  using Result = std::invoke_result_t<Task&, std::size_t>;
  if constexpr (std::is_void_v<Result>) {
    TaskRunner(threads, count, std::move(task), nullptr).wait_all();
  } else {
    return WorkPool<Result>(threads, count, std::move(task)).results();
  }
}

}  // namespace bladestab
