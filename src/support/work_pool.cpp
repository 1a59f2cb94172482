#include "support/work_pool.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace bladestab {

int worker_threads(int requested) {
  return requested > 0 ? requested : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

TaskRunner::TaskRunner(int threads, std::size_t count, std::function<void(std::size_t)> run,
                       Cancellation* cancellation)
    : count_(count),
      run_(std::move(run)),
      cancellation_(cancellation ? cancellation : &own_),
      first_failure_(std::numeric_limits<std::size_t>::max()),
      end_(count, End::pending),
      failure_(count) {
  const std::size_t helpers = std::min<std::size_t>(worker_threads(threads) - 1, count);
  for (std::size_t h = 0; h < helpers; ++h) helpers_.emplace_back([this] { run_unstarted(); });
}

TaskRunner::~TaskRunner() {
  next_ = count_;  // where the caller leaves early (an exception), no task starts any more
  for (std::thread& t : helpers_) t.join();
}

// A task starts unless one before it failed or the run was cancelled from outside: the tasks
// before a failure all run, so the lowest failing index is the one of a run in turn.
void TaskRunner::run_unstarted() {
  for (std::size_t i = next_++; i < count_; i = next_++) {
    End end = End::skipped;
    std::exception_ptr failure;
    const bool cancelled_from_outside = cancellation_->cancelled() && first_failure_ == std::numeric_limits<std::size_t>::max();
    if (i < first_failure_ && !cancelled_from_outside && !stopped_) {
      try {
        run_(i);
        end = End::done;
      } catch (const WorkCancelled&) {
        end = End::skipped;
        stopped_ = true;  // it stopped for a cancellation: the tasks after it do not start
      } catch (...) {
        end = End::failed;
        failure = std::current_exception();
        for (std::size_t f = first_failure_; i < f && !first_failure_.compare_exchange_weak(f, i);) {
        }
      }
    }
    {
      std::lock_guard<std::mutex> hold(lock_);
      end_[i] = end;
      failure_[i] = failure;
      ++settled_count_;
      cancel_after_failure();
    }
    settled_.notify_all();
  }
}

// The flag the running tasks poll is set once a task has failed and every task before it has
// ended: a task before the failure, which a run in turn finishes (or fails in) first, is never cut
// short, so what the pool reports does not depend on the thread count. Called with lock_ held.
void TaskRunner::cancel_after_failure() {
  const std::size_t failed = first_failure_;
  if (failed == std::numeric_limits<std::size_t>::max()) return;
  const auto before = end_.begin() + static_cast<std::ptrdiff_t>(failed);
  if (std::none_of(end_.begin(), before, [](End e) { return e == End::pending; })) cancellation_->cancel();
}

void TaskRunner::rethrow_first(std::unique_lock<std::mutex>& lock) {
  settled_.wait(lock, [this] { return settled_count_ == count_; });
  for (std::size_t i = 0; i < count_; ++i) {
    if (end_[i] == End::failed) std::rethrow_exception(failure_[i]);
  }
  throw WorkCancelled();
}

// Task i and every task before it settled: the lowest failure among them is the one a run in turn
// meets first, whatever order the caller asks in and whichever thread ran what.
void TaskRunner::wait_for(std::size_t i) {
  if (i >= count_) throw std::out_of_range("TaskRunner::wait_for: no such task");
  run_unstarted();
  std::unique_lock<std::mutex> lock(lock_);
  const auto through_i = end_.begin() + static_cast<std::ptrdiff_t>(i) + 1;
  settled_.wait(lock, [&] { return std::none_of(end_.begin(), through_i, [](End e) { return e == End::pending; }); });
  for (std::size_t j = 0; j <= i; ++j) {
    if (end_[j] == End::failed) std::rethrow_exception(failure_[j]);
  }
  if (end_[i] == End::skipped) rethrow_first(lock);
}

void TaskRunner::wait_all() {
  run_unstarted();
  std::unique_lock<std::mutex> lock(lock_);
  settled_.wait(lock, [this] { return settled_count_ == count_; });
  if (std::any_of(end_.begin(), end_.end(), [](End e) { return e != End::done; })) rethrow_first(lock);
}

}  // namespace bladestab
