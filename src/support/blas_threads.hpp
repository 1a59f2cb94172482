#pragma once
// OpenBLAS threads: the analyses multiply many small matrices, where OpenBLAS's thread pool
// spends more time spinning than computing, and the map sweeps run their own worker threads.
// The pthread build starts its pool when the library loads, and a pool told to use one thread
// still spins in sched_yield for ~10^8 cycles before it sleeps: on two cores that is most of a
// short run's time (measured: 37 % of a `stability` run's CPU time in sched_yield). So the pool
// is stopped, not only narrowed. `blas_thread_shutdown_` exists only in the pthread build; the
// weak reference leaves the serial and OpenMP builds alone.
extern "C" void openblas_set_num_threads(int);
extern "C" void blas_thread_shutdown_(void) __attribute__((weak));

namespace bladestab {

inline void use_single_threaded_blas() {
  openblas_set_num_threads(1);
  if (blas_thread_shutdown_) blas_thread_shutdown_();
}

}  // namespace bladestab
