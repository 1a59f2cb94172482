#include "support/work_pool.hpp"

#include <algorithm>
#include <limits>

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
    if (i < first_failure_ && !cancelled_from_outside) {
      try {
        run_(i);
        end = End::done;
      } catch (const WorkCancelled&) {
        end = End::skipped;
      } catch (...) {
        end = End::failed;
        failure = std::current_exception();
        for (std::size_t f = first_failure_; i < f && !first_failure_.compare_exchange_weak(f, i);) {
        }
        cancellation_->cancel();
      }
    }
    {
      std::lock_guard<std::mutex> hold(lock_);
      end_[i] = end;
      failure_[i] = failure;
      ++settled_count_;
    }
    settled_.notify_all();
  }
}

void TaskRunner::rethrow_first(std::unique_lock<std::mutex>& lock) {
  settled_.wait(lock, [this] { return settled_count_ == count_; });
  for (std::size_t i = 0; i < count_; ++i) {
    if (end_[i] == End::failed) std::rethrow_exception(failure_[i]);
  }
  throw WorkCancelled();
}

void TaskRunner::wait_for(std::size_t i) {
  run_unstarted();
  std::unique_lock<std::mutex> lock(lock_);
  settled_.wait(lock, [this, i] { return end_.at(i) != End::pending; });
  if (end_[i] == End::failed) std::rethrow_exception(failure_[i]);
  if (end_[i] == End::skipped) rethrow_first(lock);
}

void TaskRunner::wait_all() {
  run_unstarted();
  std::unique_lock<std::mutex> lock(lock_);
  settled_.wait(lock, [this] { return settled_count_ == count_; });
  if (std::any_of(end_.begin(), end_.end(), [](End e) { return e != End::done; })) rethrow_first(lock);
}

}  // namespace bladestab
