#pragma once
// OpenBLAS threads: the analyses multiply many small matrices, where OpenBLAS's thread pool
// spends more time spinning than computing, and the map sweeps run their own worker threads.
extern "C" void openblas_set_num_threads(int);
extern "C" int openblas_get_num_threads(void);

namespace bladestab {

inline void use_single_threaded_blas() { openblas_set_num_threads(1); }

}  // namespace bladestab
