#pragma once
// How many threads an analysis may run at once: `requested`, or one per core for 0. Analyses that
// run parts side by side (the map's points, the sweep's values, the error budget's variants, the
// Campbell estimate's richer models) take it from their options; 1 runs everything in turn on the
// calling thread.
#include <algorithm>
#include <future>
#include <thread>

namespace bladestab {

inline int worker_threads(int requested) {
  return requested > 0 ? requested : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// A task beside the caller's work when a second thread is allowed, else run when its result is
// asked for (on the caller's thread).
inline std::launch beside_or_deferred(int threads) {
  return worker_threads(threads) > 1 ? std::launch::async : std::launch::deferred;
}

}  // namespace bladestab
