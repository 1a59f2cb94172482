#pragma once
// Sixth-order Magnus propagator for a linear system ẋ = A(t) x (Blanes, Casas & Ros 2000,
// three Gauss–Legendre points per step). The constant part of A is exponentiated exactly, so
// stiff but slowly modulated systems need few steps. Knows nothing of blades: φ is a function.
#include <functional>

#include <Eigen/Dense>

namespace bladestab {

// X(t1) with X(t0) = I, in `steps` equal steps, for A(t) = A₀ + φ(t) B (the blade: a constant part
// and the tip load's). Every commutator of the expansion is then a fixed combination of nine nested
// commutators of A₀ and B, formed once, so a step costs one exponential and one product.
Eigen::MatrixXd magnus_propagator(const Eigen::MatrixXd& A0, const Eigen::MatrixXd& B,
                                  const std::function<double(double)>& phi, double t0, double t1, int steps);

// The work of one step on an n-state system in the unit of every work budget, the flops of a dense
// LAPACK eigensolver (boundary_level_flops, cli::dense_flops_per_second): the degree-18
// exponential's five products and a squaring or two, and the product with the propagator so far,
// 16 n³ flops, run 4–5 times as fast as dgeev's; forming the step's exponent adds ~13 n² at the
// speed of memory. Measured on one core: 3.7 µs a step at n = 13, 14 µs at 25, 0.67 ms at 97
// (this gives 4.3, 23 and 1030 µs at 4 Gflop/s).
inline double magnus_step_work(Eigen::Index states) {
  const double n = static_cast<double>(states);
  return 4 * n * n * n + 50 * n * n;
}

}  // namespace bladestab
