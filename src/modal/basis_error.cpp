#include "bladestab/modal/basis_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "bladestab/blade/damping.hpp"
#include "bladestab/base/input_error.hpp"

namespace bladestab {
namespace {

constexpr int max_terms = 200;
// Convergence rates p of f_N − f_∞ ∝ N^−p that the bisection resolves (beyond max_rate the tail
// is |f₁ − f₂|), and the fastest rate the estimate trusts for the sine basis. Its V_n force
// v'(0) = 0, which a Timoshenko root does not have: an O(1/N) error, so p → 1 as N grows, and the
// faster pre-asymptotic rate measured from N, 2N, 4N understates the tail (measured against the
// closed form, d̄ = 0.01 and 0.1, N = 10–40: estimate/true 0.93–1.0 with the measured p);
// 0.9, 10 % below the asymptotic rate, is the margin (tests/test_modes.cpp).
constexpr double min_rate = 0.05, max_rate = 40, max_trusted_rate = 0.9;
// Exponential convergence: |f_N − f_ref| misses the richer model's own error; measured on the
// paper blade's boundaries (N = 8 against 12, truth N = 14): 0.9985–0.9999 of the true error.
// 10 % margin.
constexpr double exponential_margin = 1.1;
// The rate a kinked table's estimate trusts (basis_convergence): below the measured 2.5–4.
constexpr double kinked_trusted_rate = 2;
// The rate an unresolved table's estimate trusts: below the measured 0.83 (mode 4 of a table with a
// step at mid-span, 24–96 terms; mode 1: 0.94; the fan blade at 8 terms: about 1.5).
constexpr double unresolved_trusted_rate = 0.75;
// The fastest rates granted when asking whether raising is futile: for a kinked table's
// frequencies the upper measured 4 (terms_for_tolerance); for the rest, and for what depends on
// the shapes (multipliers, transients: a shape converges at half its eigenvalue's rate), 2, twice
// the sine basis' asymptotic 1 and a step's about 1.
constexpr double kinked_fastest_rate = 4, other_fastest_rate = 2;
// An estimate from this on (relative) shows no rate: the mode is not yet resolved by the basis
// (pre-asymptotic), or has no counterpart in the richer model (1). The fan blade's modes 80–90 at
// 16–40 terms: estimates 1–8.4 with no trend, 1e-7 at 60 terms.
constexpr double unresolved_estimate = 0.1;

// How much |f_N − f_M| understates the error of f_N when f_N − f_∞ ∝ N^−p (ratio = N/M < 1):
// 1/(1 − (N/M)^p).
double algebraic_tail(double ratio, double rate) { return 1 / (1 - std::pow(ratio, rate)); }

ModalSolution modes_of(const BladeModel& model, const Scene& scene, int count, EigenSolverKind solver) {
  const double speed = scene.operation.speed_rad_s;
  return solve_modes(model, system_at(model, speed, damping_matrix(model, scene.damping, speed)), speed, count,
                     solver);
}

// Frequency (or |eigenvalue| for a non-oscillating mode) of the `rank`-th mode of `family` in
// `reference` among those that oscillate (`by_frequency`) or among those that do not; none if it
// has no counterpart. Apart, because a heavy damping puts overdamped roots of a family between its
// oscillating modes, more of them in a richer model (Rayleigh ζ = 0.3 at 600 rad/s: the 7th bending
// mode, 3104 Hz, had an overdamped root of 27 terms as its counterpart, error 1).
std::optional<double> counterpart(const ModalSolution& reference, ModeFamily family, int rank, bool by_frequency) {
  int seen = 0;
  for (const Mode& r : reference.modes) {
    if (r.family != family || (r.frequency_hz > 0) != by_frequency || seen++ != rank) continue;
    return by_frequency ? r.frequency_hz : std::abs(r.eigenvalue);
  }
  return std::nullopt;
}

}  // namespace

// Relative error of f₁ (n[0] terms) from the same mode of richer models, f[1] (n[1] terms) and,
// for algebraic convergence, f[2] (n[2] ≥ n[1] terms). Algebraic convergence f_N − f_∞ ≈ C N^−p (sine): |f₁ − f₂| understates the
// tail by 1/(1 − (n₁/n₂)^p), 1.4–2× for the sine basis; p comes from the ratio of the two
// differences (at most max_trusted_rate) and f₁ − f_∞ ≈ (f₁ − f₂) / (1 − (n₁/n₂)^p).
// Exponential convergence (Legendre): exponential_margin · |f₁ − f₂|.
BasisTail basis_tail(const std::vector<double>& f, const std::vector<int>& n, BasisConvergence convergence) {
  const double d1 = f[0] - f[1];
  if (convergence == BasisConvergence::kinked || convergence == BasisConvergence::unresolved) {
    const double rate = convergence == BasisConvergence::kinked ? kinked_trusted_rate : unresolved_trusted_rate;
    const double factor = algebraic_tail(static_cast<double>(n[0]) / n[1], rate);
    return {factor * std::abs(d1) / std::abs(f[1]), factor};
  }
  if (f.size() == 2 || d1 == 0) return {exponential_margin * std::abs(d1) / std::abs(f[1]), exponential_margin};
  double p = max_trusted_rate;  // the richest model is capped (n[2] = n[1])
  if (n[2] > n[1]) {
    const auto ratio = [&](double q) {  // d2/d1 for f_N = C N^−q, decreasing in q
      return (std::pow(n[1], -q) - std::pow(n[2], -q)) / (std::pow(n[0], -q) - std::pow(n[1], -q));
    };
    const double r = (f[1] - f[2]) / d1;
    double lo = min_rate, hi = max_rate;
    if (r >= ratio(lo)) hi = lo;
    if (r <= ratio(hi)) lo = hi;
    for (int i = 0; i < 60 && hi > lo; ++i) ((ratio(0.5 * (lo + hi)) > r) ? lo : hi) = 0.5 * (lo + hi);
    p = std::min(lo, max_trusted_rate);  // lo: the slower rate of the bracket, the larger tail
  }
  const double factor = algebraic_tail(static_cast<double>(n[0]) / n[1], p);
  return {factor * std::abs(d1) / std::abs(f[1]), factor};
}

namespace {

// Frequencies (|eigenvalue| for non-oscillating modes) and terms of the models compared: the
// base, then the richer ones.
std::vector<double> compare(const std::vector<ModalSolution>& models, const std::vector<int>& terms,
                            BasisConvergence convergence) {
  std::vector<double> error;
  int rank_in_family[mode_family_count][2] = {};  // [family][oscillating]
  for (const Mode& m : models[0].modes) {
    const bool by_frequency = m.frequency_hz > 0;
    const int rank = rank_in_family[static_cast<int>(m.family)][by_frequency]++;
    std::vector<double> f{by_frequency ? m.frequency_hz : std::abs(m.eigenvalue)};
    for (std::size_t k = 1; k < models.size(); ++k) {
      const std::optional<double> c = counterpart(models[k], m.family, rank, by_frequency);
      if (c && *c > 0) f.push_back(*c);
    }
    error.push_back(f.size() == models.size() ? basis_tail(f, terms, convergence).relative : 1.0);  // no counterpart: nothing is known
  }
  return error;
}

}  // namespace

ErrorBudget ConvergedModes::budget(std::size_t k) const {
  ErrorBudget b;
  b.basis = relative_error[k];
  b.method = rounding[k];
  return b;
}

double frequency_rounding(const Eigen::MatrixXd& absolute_stiffness, const Eigen::VectorXd& absolute_shape,
                          double stiffness_form) {
  const double spread = absolute_shape.dot(absolute_stiffness * absolute_shape) / std::abs(stiffness_form);
  return std::max(eigensolver_rounding, 10 * std::numeric_limits<double>::epsilon() * spread);
}

ErrorBudget ConvergedModes::worst_budget() const {
  ErrorBudget worst;
  for (std::size_t k = 0; k < relative_error.size(); ++k) worst.raise_to(budget(k));
  return worst;
}

double ConvergedModes::max_relative_error() const {
  return relative_error.empty() ? 0 : *std::max_element(relative_error.begin(), relative_error.end());
}

int reference_terms(BasisKind basis, int terms) {
  const int richer = basis == BasisKind::legendre ? terms + std::max(4, terms / 2) : 2 * terms;
  return std::min(richer, max_terms + 40);
}

ReferenceSolves reference_solves(ModelSpec spec, bool two_planes, bool damped, bool within_static_limits) {
  ReferenceSolves solves;
  for (int model = 0; model <= (spec.basis == BasisKind::sine ? 2 : 1); ++model) {
    const int dofs = dof_layout(spec, two_planes).size();
    solves.flops += whole_eigensolve_flops(dofs, damped, within_static_limits);
    solves.largest_dofs = std::max(solves.largest_dofs, dofs);
    spec.terms = reference_terms(spec.basis, spec.terms);
  }
  return solves;
}

BasisConvergence basis_convergence(const BladeSpec& blade, BasisKind basis, int terms) {
  if (basis == BasisKind::sine) return BasisConvergence::sine;
  if (blade.sections.size() <= 2) return BasisConvergence::exponential;
  double closest = 1;
  for (std::size_t k = 1; k < blade.sections.size(); ++k) {
    closest = std::min(closest, blade.sections[k].span_fraction - blade.sections[k - 1].span_fraction);
  }
  return closest * terms < 2 ? BasisConvergence::unresolved : BasisConvergence::kinked;
}

double basis_tail_factor(BasisConvergence convergence) {
  switch (convergence) {
    case BasisConvergence::exponential: return exponential_margin;
    case BasisConvergence::kinked: return algebraic_tail(2.0 / 3, kinked_trusted_rate);
    case BasisConvergence::unresolved: return algebraic_tail(2.0 / 3, unresolved_trusted_rate);
    case BasisConvergence::sine: break;
  }
  return algebraic_tail(0.5, max_trusted_rate);
}

namespace {

// basis_can_reach with the fastest rate granted a kinked table, `kinked_rate`.
bool reachable(const BladeSpec& blade, const ModelSpec& spec, double estimate, double tolerance,
               std::optional<BasisRound> before, double kinked_rate) {
  if (spec.terms >= max_terms) return false;
  const auto unresolved_at = [&](int terms) {
    return basis_convergence(blade, spec.basis, terms) == BasisConvergence::unresolved;
  };
  const BasisConvergence convergence = basis_convergence(blade, spec.basis, spec.terms);
  if (convergence == BasisConvergence::exponential) return true;
  if (!unresolved_at(max_terms) && (unresolved_at(spec.terms) || (before && unresolved_at(before->terms)))) return true;
  // Algebraic convergence: the estimate falls like N^−p (sine: p ≤ 1 asymptotically, v'(0) = 0 is
  // an O(1/N) error; a step: about 1; kinked: frequencies 2.5–4). If even the fastest of these
  // would need more than max_terms, raising is futile.
  const double rate = convergence == BasisConvergence::kinked ? kinked_rate : other_fastest_rate;
  return spec.terms * std::pow(estimate / tolerance, 1 / rate) <= max_terms;
}

// A kinked table's frequency estimate that shows no rate: 0.1 or more (a mode not resolved yet, or
// without a counterpart), or fallen faster than N^−4 since the round before (a mode being resolved).
bool frequency_shows_no_rate(const BladeSpec& blade, const ModelSpec& spec, double estimate,
                             std::optional<BasisRound> before) {
  if (basis_convergence(blade, spec.basis, spec.terms) != BasisConvergence::kinked) return false;
  if (estimate >= unresolved_estimate) return true;
  return before && before->terms < spec.terms && before->estimate > estimate &&
         std::log(before->estimate / estimate) >
             kinked_fastest_rate * std::log(static_cast<double>(spec.terms) / before->terms);
}

}  // namespace

bool basis_can_reach(const BladeSpec& blade, const ModelSpec& spec, double estimate, double tolerance,
                     std::optional<BasisRound> before) {
  return reachable(blade, spec, estimate, tolerance, before, other_fastest_rate);
}

std::optional<int> terms_for_tolerance(const BladeSpec& blade, const ModelSpec& spec, double estimate, double tolerance,
                                       std::optional<BasisRound> before) {
  if (spec.terms >= max_terms) return std::nullopt;
  const bool no_rate = frequency_shows_no_rate(blade, spec, estimate, before);
  if (!no_rate && !reachable(blade, spec, estimate, tolerance, before, kinked_fastest_rate)) return std::nullopt;
  if (spec.basis == BasisKind::sine) return std::min(max_terms, 2 * spec.terms);
  // A mode not yet resolved tells nothing of the terms it needs: grow them geometrically.
  const int step = estimate >= unresolved_estimate ? std::max(2, spec.terms / 2) : 2;
  return std::min(max_terms, spec.terms + step);
}

int resolvable_mode_count(const BladeSpec& blade, const ModelSpec& spec) {
  ModelSpec richest = spec;
  richest.terms = max_terms;
  return dof_layout(richest, blade.two_planes()).size() / 2;
}

void check_mode_count(const BladeSpec& blade, const ModelSpec& spec, int count) {
  const int resolvable = resolvable_mode_count(blade, spec);
  if (count > resolvable) {
    throw ParameterError("count", fmt::format("{}: more modes than raising the terms can resolve, at most {} (half the "
                                              "dofs of {} terms per field); ask for fewer",
                                              count, resolvable, max_terms));
  }
}

void check_tolerance(double tolerance) {
  if (!(tolerance > 0 && tolerance < 1)) throw ParameterError("tolerance", fmt::format("{}: must be in (0, 1)", tolerance));
  if (tolerance <= eigensolver_rounding) {
    throw ParameterError("tolerance", fmt::format("{}: must be above {:g}, the eigensolver's rounding that every "
                                                  "estimate includes",
                                                  tolerance, eigensolver_rounding));
  }
}

ParameterError tolerance_not_met(double tolerance, const ModelSpec& spec, double estimate) {
  return ParameterError("tolerance", fmt::format("{}: not met with {} terms per field (estimated error {:.2g}); "
                                "use {}a looser tolerance",
                                tolerance, spec.terms, estimate,
                                spec.basis == BasisKind::sine ? "model.basis = \"legendre\" (for model.basis = \"sine\") or " : ""));
}

ParameterError tolerance_below_rounding(double tolerance, double rounding) {
  return ParameterError("tolerance", fmt::format("{}: below the rounding of these frequencies, {:.2g} (the stiffness "
                                "form of a slender blade's low modes cancels); more terms do not lower it",
                                tolerance, rounding));
}

ConvergedModes modes_with_error_estimate(const Scene& scene, int count, EigenSolverKind solver,
                                         std::optional<double> tolerance) {
  if (tolerance) {
    check_tolerance(*tolerance);
    check_mode_count(scene.blade, scene.model, count);
  }
  ModelSpec spec = scene.model;
  std::optional<BasisRound> before;  // the round before
  while (true) {
    BladeModel model = assemble_model(scene, spec);
    ModalSolution solution = modes_of(model, scene, count, solver);
    // Richer models: one for the Legendre basis' exponential convergence, two for the sine
    // basis' algebraic one. They need more modes so that every family is represented to the same rank.
    std::vector<ModalSolution> models{solution};
    std::vector<int> terms{spec.terms};
    for (int level = 0; level < (spec.basis == BasisKind::sine ? 2 : 1); ++level) {
      ModelSpec richer = spec;
      richer.terms = reference_terms(spec.basis, terms.back());
      models.push_back(modes_of(assemble_model(scene, richer), scene, 0, EigenSolverKind::dense));
      terms.push_back(richer.terms);
    }
    std::vector<double> rounding;
    const Eigen::MatrixXd K = model.stiffness(scene.operation.speed_rad_s);
    const Eigen::MatrixXd absolute = K.cwiseAbs();
    for (const Mode& m : solution.modes) {
      rounding.push_back(frequency_rounding(absolute, m.shape.cwiseAbs(), (m.shape.adjoint() * K * m.shape)(0).real()));
    }
    ConvergedModes result{std::move(model), std::move(solution), terms.back(),
                          compare(models, terms, basis_convergence(scene.blade, spec.basis, spec.terms)), std::move(rounding)};
    // The whole estimate of every mode (basis + method), as printed, must meet the tolerance.
    const double estimate = result.worst_budget().total();
    if (!tolerance || estimate <= *tolerance) return result;
    const double rounded = *std::max_element(result.rounding.begin(), result.rounding.end());
    if (rounded > *tolerance) throw tolerance_below_rounding(*tolerance, rounded);
    const std::optional<int> next =
        terms_for_tolerance(scene.blade, spec, estimate, *tolerance, before);
    if (!next) throw tolerance_not_met(*tolerance, spec, estimate);
    before = BasisRound{spec.terms, estimate};
    spec.terms = *next;
  }
}

}  // namespace bladestab
