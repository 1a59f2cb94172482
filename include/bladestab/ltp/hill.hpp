#pragma once
// Floquet multipliers from the Hill matrix of an LTP system (docs/theory.md §4), at a fixed
// truncation q: the building blocks of floquet_multipliers' Hill methods.
#include <Eigen/Dense>

#include "bladestab/ltp/linear_periodic_system.hpp"

namespace bladestab {

// H: blocks H_jk = A_{j−k} − i k θ δ_jk I, j, k = −q..q.
Eigen::MatrixXcd hill_matrix(const LinearPeriodicSystem& system, int q);
// Bolotin/Hill with the classical sorting: of the n(2q + 1) exponents the n with the smallest |Im λ|.
Eigen::VectorXcd hill_multipliers(const LinearPeriodicSystem& system, int q);
// Koopman–Hill (Bayer & Leine 2023): Φ(T) ≈ C e^{HT} W, sorting-free.
Eigen::VectorXcd koopman_hill_multipliers(const LinearPeriodicSystem& system, int q);

}  // namespace bladestab
