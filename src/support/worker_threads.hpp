#pragma once
// How many threads an analysis may run at once: `requested`, or one per core for 0. Analyses that
// run parts side by side (the map's points, the sweep's values, the error budget's variants, the
// Campbell estimate's richer models) take it from their options; 1 runs everything in turn on the
// calling thread.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <future>
#include <thread>
#include <vector>

namespace bladestab {

inline int worker_threads(int requested) {
  return requested > 0 ? requested : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// A task beside the caller's work when a second thread is allowed, else run when its result is
// asked for (on the caller's thread).
inline std::launch beside_or_deferred(int threads) {
  return worker_threads(threads) > 1 ? std::launch::async : std::launch::deferred;
}

// Independent tasks run beside the caller's own work: up to threads − 1 helper threads take them
// in the order given (put the costliest first), and whatever no helper has started when a result
// is asked for runs on the caller's thread. So the caller never idles while tasks wait, and no
// more than `threads` run at once; with one thread every task runs in turn, when asked for.
template <class Result>
class SideTasks {
 public:
  SideTasks(int threads, std::vector<std::function<Result()>> tasks) : tasks_(tasks.size()) {
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      tasks_[i] = std::packaged_task<Result()>(std::move(tasks[i]));
      results_.push_back(tasks_[i].get_future());
    }
    const int helpers = std::min<int>(worker_threads(threads) - 1, static_cast<int>(tasks_.size()));
    for (int h = 0; h < helpers; ++h) helpers_.emplace_back([this] { run_unstarted(); });
  }
  SideTasks(const SideTasks&) = delete;
  SideTasks& operator=(const SideTasks&) = delete;
  ~SideTasks() {
    next_ = tasks_.size();  // where the caller left early (an exception), no task starts any more
    for (std::thread& t : helpers_) t.join();
  }

  // The result of task `i` (rethrowing its exception); at most once per task.
  Result get(std::size_t i) {
    run_unstarted();
    return results_.at(i).get();
  }

 private:
  void run_unstarted() {
    for (std::size_t i = next_++; i < tasks_.size(); i = next_++) tasks_[i]();
  }

  std::vector<std::packaged_task<Result()>> tasks_;
  std::vector<std::future<Result>> results_;
  std::atomic<std::size_t> next_{0};
  std::vector<std::thread> helpers_;
};

}  // namespace bladestab
