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
// exponential's five products, a squaring, and the product with the propagator so far, 14 n³
// flops, run about 7 times as fast as dgeev's; forming the step's exponent adds ~13 n² at the speed
// of memory. Measured on one core (bench/work_calibration.cpp, 28 Nov 2026): 1.5 µs a step at n = 13,
// 5.7 µs at 25, 0.23 ms at 97, 0.87 ms at 146, 6.5 ms at 270; this counts 1.6–2.5× those (2.8 µs,
// 14 µs, 0.55 ms, 1.8 ms and 11 ms at 4 Gflop/s).
inline double magnus_step_work(Eigen::Index states) {
  const double n = static_cast<double>(states);
  return 2 * n * n * n + 40 * n * n;
}
}  // namespace bladestab
