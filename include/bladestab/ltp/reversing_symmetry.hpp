#pragma once
// A time-reversal symmetry of an LTP system (linear_periodic_system.hpp, docs/theory.md §4.5): a
// signature R = diag(±1) with R A₀ R = −A₀ and R B R = −B, on an even coefficient f(−t) = f(t)
// (every f_m real). Then y(t) = R x(T − t) solves the same system as x, and half a period gives
// the whole monodromy:
//
//   Φ(T) = R U⁻¹ R U,   U = Φ(T/2, 0).
//
// Read from the matrices as stated, as a sparse solver reads a pattern: a conservative system
// whose coupling pairs the coordinates off in two classes, every entry joining one class to the
// other, has one; any damping (a diagonal entry) breaks it.
#include <optional>

#include <Eigen/Dense>

#include "bladestab/ltp/linear_periodic_system.hpp"

namespace bladestab {

// R's diagonal, or none. Entries up to 1e-13 of their matrix's largest are taken as the rounding of
// the coordinates' transformation (a zero coupling of two modes computes as ~1e-16): the Φ(T)
// that R gives is then that of a system within 1e-13 of the one stated.
std::optional<Eigen::VectorXd> reversing_signature(const LinearPeriodicSystem& system);
// R for A(t) = A₀ + φ(t) B alone, where the caller knows φ to be even about the middle c of the
// interval it steps: the second half then follows from the first, Φ(c + s, c) = R Φ(c, c − s)⁻¹ R.
std::optional<Eigen::VectorXd> reversing_signature(const Eigen::MatrixXd& A0, const Eigen::MatrixXd& B);

}  // namespace bladestab
