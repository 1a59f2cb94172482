#pragma once
// The Ritz basis's error and the policy that bounds it ("model only what a scene needs"): the
// richer basis a result is compared with (reference_terms) and how far its difference understates
// the error (basis_tail), the terms a tolerance needs (terms_for_tolerance), and for computed
// modes, each compared with the same mode (same family, same rank within it) of a richer model
// with the terms raised until every requested mode meets a tolerance.
#include <optional>
#include <vector>

#include "bladestab/base/error_budget.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct ConvergedModes {
  BladeModel model;                   // the model the modes belong to
  ModalSolution solution;
  int reference_terms = 0;            // terms of the richest model used for the estimate
  std::vector<double> relative_error; // estimated |f_N − f_∞| / f_∞ per mode (the basis part)
  std::vector<double> rounding;       // frequency_rounding per mode (the method part)
  double max_relative_error() const;
  // Mode k's whole error: basis = relative_error[k], method = rounding[k]; no cut-off
  // (reduction 0), no load (0).
  ErrorBudget budget(std::size_t k) const;
  ErrorBudget worst_budget() const;  // each part the largest over the modes
};

// Relative rounding of a dense eigensolve of the modal problem (LAPACK, double precision, a few
// hundred dofs: ≲ 1e-13 on the frequencies; 1e-12 bounds it) where the problem is well scaled.
inline constexpr double eigensolver_rounding = 1e-12;

// Relative rounding of a computed frequency with shape q: eigensolver_rounding or, where larger,
// that of the stiffness form qᴴKq itself, which cancels for a slender blade's low modes (their
// shear energy κGA∫(v' − θ)² is a small difference of large terms): 10·ε·(|q|ᵀ|K||q|)/(qᴴKq),
// ε the machine epsilon, half of it for ω = (k/m)^½ and 20 for the summation (measured on the
// paper blade's first mode, |q|ᵀ|K||q|/qᴴKq = 4.9e3 at rest: dense eigenvalue and Rayleigh
// quotient 1.8e-12 apart, above a flat 1e-12; at d̄ = 0.001 the ratio is 4.9e5).
// `absolute_stiffness` is |K| entry by entry.
double frequency_rounding(const Eigen::MatrixXd& absolute_stiffness, const Eigen::VectorXd& absolute_shape,
                          double stiffness_form);

// Terms of the richer model used to estimate the error of an N-term model: Legendre (exponential
// convergence) N + max(4, N/2); sine (algebraic convergence) 2N, and a third level 4N to measure
// the rate of convergence.
int reference_terms(BasisKind basis, int terms);

// One whole dense eigensolve (whole_eigensolve_flops, modes.hpp) of a model of `spec` and one of
// each richer model its estimate compares with (one for the Legendre basis, two for the sine
// basis, reference_terms): their flops together and the largest model's dofs.
struct ReferenceSolves {
  double flops = 0;
  int largest_dofs = 0;
};
ReferenceSolves reference_solves(ModelSpec spec, bool two_planes, bool damped, bool within_static_limits = false);

// How fast the Ritz basis converges on a blade, which sets how far one comparison |f_N − f_ref|
// understates the error and whether more terms can reach a tolerance:
//   exponential  Legendre on smooth properties (the uniform blade, or a table of two stations);
//   kinked       Legendre on a section table with stations inside the span: linear between the
//                stations, the properties have kinks there, the modes' third derivatives jump,
//                and the frequencies converge algebraically, about like N^−3 (measured on the
//                example fan blade, N = 16…60: rates 2.5–4); the estimate trusts N^−2;
//   unresolved   Legendre on a table with two stations closer than 2/N of the span, which N terms
//                do not resolve: a step (stations at 0.5 and 0.5000001) converges like N^−0.83
//                to N^−1 at every N, the fan blade's 0.2 at N = 8 like N^−1.5 (its estimate at
//                N^−2 fell 1.25× short); the estimate trusts N^−0.75;
//   sine         the sine basis (its V_n force v'(0) = 0: an O(1/N) error at a Timoshenko root).
enum class BasisConvergence { exponential, kinked, unresolved, sine };

// For a model of `terms` terms per field.
BasisConvergence basis_convergence(const BladeSpec& blade, BasisKind basis, int terms);

// How much a single comparison |f_N − f_ref| (ref: reference_terms) understates the error of an
// N-term result: 1.1 for exponential convergence (the margin covers the richer model's own
// error); 1/(1 − (2/3)²) = 1.8 for a kinked table at the trusted rate 2 (N against ≥ 1.5 N), and
// 1/(1 − (2/3)^0.75) = 3.8 for an unresolved one; for sine (f_N − f_∞ ∝ N^−p, p → 1)
// 1/(1 − 2^−0.9) = 2.15, the rate its modes' estimate trusts at most.
double basis_tail_factor(BasisConvergence convergence);

// Relative basis error of f[0] (n[0] terms) from the same mode in richer models: f[1] (n[1]
// terms) and, for the sine basis' algebraic convergence, f[2] (n[2] terms). `relative` is
// `factor` · |f[0] − f[1]| / |f[1]|: 1.1 for exponential convergence, 1/(1 − (n₀/n₁)²) for a
// kinked table, 1/(1 − (n₀/n₁)^p) for the sine basis at the measured rate p (at most 0.9).
struct BasisTail {
  double relative = 0;
  double factor = 1;
};
BasisTail basis_tail(const std::vector<double>& f, const std::vector<int>& n, BasisConvergence convergence);

// The terms and the whole estimate of a round of raising before the present one.
struct BasisRound {
  int terms = 0;
  double estimate = 0;
};

// Whether raising the terms from N (`spec`) on `blade` can bring a basis error `estimate` within
// `tolerance`: not when N is at the limit of 200, nor for algebraic convergence (sine, kinked, a step
// no 200 terms resolve) when even a convergence like N^−2 would need more than 200 terms. A table
// that N terms do not resolve but 200 would is raised regardless, and so is one that the round
// before (`before`) did not resolve: an estimate there shows no rate (the fan blade in
// `campbell`: 1.1 at 4 terms, 0.025 at 10, 3.4e-4 at 12, 1.7e-5 at 14). Every analysis that
// raises the terms asks this (or terms_for_tolerance) before it does, so a tolerance out of the
// basis' reach is said at once.
bool basis_can_reach(const BladeSpec& blade, const ModelSpec& spec, double estimate, double tolerance,
                     std::optional<BasisRound> before = std::nullopt);

// The terms to try next for frequencies within `tolerance` when the estimate of a model of `spec`
// on `blade` is `estimate` (`before`: the round before): sine 2N, Legendre N + 2, or 1.5N for an
// estimate of 0.1 or more (at most 200); none where raising is futile. As basis_can_reach, but a
// kinked table's frequencies converge like N^−2.5 to N^−4, and N^−4 is granted them; and an
// estimate that shows no rate is raised regardless: 0.1 or more (a mode the basis does not resolve
// yet, or without a counterpart in the richer model), or fallen faster than N^−4 since the round
// before (a mode being resolved: the fan blade's 90th, ≥ 0.1 at 36 terms, 2.4e-3 at 54, 1e-6 at 65).
std::optional<int> terms_for_tolerance(const BladeSpec& blade, const ModelSpec& spec, double estimate, double tolerance,
                                       std::optional<BasisRound> before = std::nullopt);

// The modes that raising the terms can resolve: half the dofs of the richest model (200 terms per
// field), the part of a Ritz spectrum that ever converges (the fan blade's 90th mode took 330 dofs
// at 1e-6).
int resolvable_mode_count(const BladeSpec& blade, const ModelSpec& spec);
// ParameterError on `count` (the modes asked for, lowest first) beyond resolvable_mode_count.
void check_mode_count(const BladeSpec& blade, const ModelSpec& spec, int count);

// ParameterError on `tolerance` unless 0 < tolerance < 1 and tolerance > 1e-12, the
// eigensolver's rounding that every estimate includes.
void check_tolerance(double tolerance);

// The one-line InputError for a tolerance that raising the terms cannot meet.
ParameterError tolerance_not_met(double tolerance, const ModelSpec& spec, double estimate);
// ... and for one below the rounding of the frequencies themselves (more terms do not lower it).
ParameterError tolerance_below_rounding(double tolerance, double rounding);

// Modes of `scene` at its speed with their error estimates. With a tolerance, the number of terms
// starts at the scene's and grows until every one of the `count` lowest modes has a whole
// estimate (basis + method) within it; an InputError when raising cannot get there
// (terms_for_tolerance) or the tolerance is out of range (check_tolerance).
ConvergedModes modes_with_error_estimate(const Scene& scene, int count, EigenSolverKind solver,
                                         std::optional<double> tolerance = std::nullopt);

}  // namespace bladestab
