#pragma once
// The monodromy matrix Φ(T) of an LTP system (linear_periodic_system.hpp) and what is read from
// it: its eigenvalues, the Floquet multipliers ρ (docs/theory.md §4).
#include <Eigen/Dense>

#include "bladestab/base/numerical_error.hpp"

#include "bladestab/ltp/linear_periodic_system.hpp"

namespace bladestab {

// Φ(T) by the sixth-order Magnus propagator in `steps` equal steps; over half the period (steps/2
// of them) where the system has a reversing symmetry (reversing_symmetry.hpp), unless
// `whole_period`: at a Jordan pair (a stability boundary) two multipliers move like the square
// root of Φ's rounding, which U⁻¹ raises by U's condition.
Eigen::MatrixXd magnus_monodromy(const LinearPeriodicSystem& system, int steps, bool whole_period = false);
// The work of one of magnus_monodromy's steps per period (magnus_step_work): half a Magnus step's
// where it steps half the period.
double monodromy_step_work(const LinearPeriodicSystem& system);
// Its eigenvalues, sorted by |ρ|, largest first; NumericalError if Φ(T) overflowed.
Eigen::VectorXcd monodromy_multipliers(const LinearPeriodicSystem& system, int steps);
// Φ(T) integrated by RKF45 at relative tolerance `rtol` (all fundamental solutions at once).
Eigen::MatrixXd rkf45_monodromy(const LinearPeriodicSystem& system, double rtol);
// The most Magnus steps per period any monodromy takes (floquet.hpp refuses a system that needs more).
inline constexpr int max_magnus_steps = 1 << 17;
// Magnus steps per period below which the step's h‖A‖ exceeds 2 (the series would diverge).
int minimum_magnus_steps(const LinearPeriodicSystem& system);
// The error of a monodromy over `period` that overflows at step counts that are short enough
// (StepDoubling::overflowed): unstable, max|ρ| > 1e308, so max Re λ > ln(1e308)/period: the system
// grows past the double range within one period.
NumericalError monodromy_overflow(double period);
// Eigenvalues of Φ sorted by |ρ|, largest first; NumericalError if they do not converge.
Eigen::VectorXcd sorted_eigenvalues(const Eigen::MatrixXd& phi);
// Largest distance |ρ_a − ρ_b| between two multiplier sets of equal size, each ρ matched to its
// nearest unused partner. Tolerances compare it with tol·max(1, max|ρ|): the small multipliers of
// a strongly unstable Φ carry rounding of order ε‖Φ‖.
double multiplier_set_distance(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b);
// Liouville: |det Φ(T) / exp(∫₀ᵀ tr A dt) − 1|, computed in logarithms.
double liouville_error(const Eigen::MatrixXd& monodromy, const LinearPeriodicSystem& system);

}  // namespace bladestab
