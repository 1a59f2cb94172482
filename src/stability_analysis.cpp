#include "bladestab/stability_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <optional>

#include <fmt/format.h>

#include "bladestab/damping.hpp"
#include "bladestab/input_error.hpp"
#include "bladestab/mode_convergence.hpp"
#include "bladestab/periodic_system.hpp"
#include "bladestab/reduction.hpp"

namespace bladestab {
namespace {

constexpr int max_terms = 200;

// One fidelity of the scene's LTP system: its basis, its reduction, its load series.
struct Fidelity {
  ModelSpec model;
  ReductionSpec reduction;
  LoadSeries load;
};

PeriodicSystem system_at(const Scene& scene, const Fidelity& f) {
  return periodic_system(assemble_model(scene.blade, f.model), scene, f.load, f.reduction);
}

// The multipliers of one fidelity: the true pulse train by its piecewise monodromy, a series by the
// requested method.
FloquetResult floquet_of(const Scene& scene, const Fidelity& f, const PeriodicSystem& sys, const FloquetOptions& o) {
  if (!f.load.exact_pulse) return floquet_multipliers(sys, o);
  if (o.method == FloquetMethod::hill || o.method == FloquetMethod::koopman_hill) {
    throw InputError(fmt::format("--method {}: Hill methods need a Fourier load; load.approximation = \"exact\" is "
                                 "integrated through each pulse (use monodromy or auto)", to_string(o.method)));
  }
  return pulse_train_multipliers(sys, pulse_train(scene), o);
}

// max|ρ| of a variant and the error of that value.
struct VariantRho {
  double rho = 0, error = 0;
};

// A variant of a Magnus answer (N steps) is integrated with N/4 and N/2 steps, and N if those
// two differ by more than `tol`: the variant's value at the finer count and its difference to the
// coarser one. The answer's coarser levels were within the ladder's Δ_N of its level N, and
// both systems carry nearly the same discretization error, which the budget's `method` part
// counts once; the variant's own difference bounds what differs. A variant stiffer than the
// ladder would start at (a richer unreduced basis), Hill answers and the exact train take the
// variant's own ladder to `tol`.
VariantRho variant_max_rho(const Scene& scene, const Fidelity& f, const FloquetResult& answer, double tol) {
  const PeriodicSystem sys = system_at(scene, f);
  const int coarsest = answer.steps / 4;
  if (coarsest >= 8 && 64 * coarsest >= minimum_magnus_steps(sys) && !f.load.exact_pulse) {
    std::optional<double> previous;
    for (int steps = coarsest; steps <= answer.steps; steps *= 2) {
      const Eigen::MatrixXd phi = magnus_monodromy(sys, steps);
      if (!phi.allFinite()) break;
      const double rho = phi.eigenvalues().cwiseAbs().maxCoeff();
      if (previous && std::abs(rho - *previous) <= tol * std::max(1.0, rho)) return {rho, std::abs(rho - *previous)};
      previous = rho;
    }
  }
  const FloquetResult r = floquet_of(scene, f, sys, {FloquetMethod::monodromy, 0, tol, false});
  return {r.max_abs_multiplier, r.error_estimate};
}

// Each part of the budget from a variant that differs from `f` in that part only.
ErrorBudget budget_of(const Scene& scene, const Fidelity& f, const FloquetResult& r, double tol) {
  ErrorBudget b;
  const double rho = r.max_abs_multiplier, variant_tol = tol / 8;
  b.method = r.error_estimate;
  // factor · |ρ − ρ_variant| plus the variant's own error.
  const auto part = [&](const Fidelity& variant, double factor) {
    const VariantRho v = variant_max_rho(scene, variant, r, variant_tol);
    return factor * std::abs(rho - v.rho) + v.error;
  };

  // The variants are independent: the richer basis on a second thread while this one does the
  // reduction's (the machine has two cores; each variant is a third of a `stability` run).
  Fidelity richer_basis = f;
  richer_basis.model.terms = reference_terms(f.model.basis, f.model.terms);
  // Algebraic convergence (sine basis): the difference to 2N understates the error up to 2×.
  std::future<double> basis = std::async(std::launch::async, part, richer_basis, f.model.basis == BasisKind::sine ? 2 : 1);

  if (f.reduction.kind == ReductionKind::automatic) {
    Fidelity richer = f;
    richer.reduction.vectors = 2 * f.reduction.vectors;
    // Galerkin projections do not converge monotonically in max|ρ|: a factor 2 of safety.
    b.reduction = part(richer, 2);
  } else if (f.reduction.kind == ReductionKind::modal && f.reduction.cutoff_hz > 0) {
    Fidelity reduced = f;
    reduced.reduction = {ReductionKind::automatic, 2 * default_reduction_vectors, 0};
    b.reduction = part(reduced, 1);
  }
  b.basis = basis.get();

  if (!f.load.cosine_approximation && !f.load.exact_pulse) {
    // The truncated series against the true pulse train it stands for.
    Fidelity exact = f;
    exact.load = exact_pulse_mean(pulse_train(scene));
    b.load = part(exact, 1);
  }
  return b;
}

}  // namespace

StabilityAnswer analyse_stability(const Scene& scene, const StabilityRequest& request) {
  Fidelity f{scene.model, scene.model.reduction, load_series(scene)};
  if (!f.load.frequency_known) {
    throw InputError("operation.speed_rad_s = 0: the pulses have no frequency; give load.pulse_frequency_hz "
                     "(in Hz, > 0) or a speed > 0");
  }
  const bool vectors_free = f.reduction.kind == ReductionKind::automatic && f.reduction.vectors == 0;
  if (vectors_free && f.load.exact_pulse) {
    // The true train integrates only through the contacts: the whole Ritz model is cheap unless the
    // contact is long against its stiffest period, and it resolves the pulse's high harmonics,
    // which the narrow tongues of the true train depend on.
    const PeriodicSystem whole = system_at(scene, {f.model, {ReductionKind::none, 0, 0}, f.load});
    const PulseTrain train = pulse_train(scene);
    if (minimum_magnus_steps(whole) * train.contact_time_s / train.period_s <= 4096) f.reduction.kind = ReductionKind::none;
  }
  if (f.reduction.kind == ReductionKind::automatic && f.reduction.vectors == 0) {
    f.reduction.vectors = default_reduction_vectors;
  }
  const double tol = request.tolerance;
  StabilityAnswer a;
  while (true) {
    const PeriodicSystem sys = system_at(scene, f);
    a.floquet = floquet_of(scene, f, sys, {request.method, request.harmonics, tol / 4, true});
    a.budget = budget_of(scene, f, a.floquet, tol);
    a.reduced_size = sys.kept_modes;
    a.full_size = sys.all_modes;
    a.theta_rad_s = sys.angular_frequency;
    const double allowed = tol * std::max(1.0, a.floquet.max_abs_multiplier);
    if (a.budget.total() <= allowed) break;
    // Raise the largest part that the scene leaves free; stop where none is.
    const ErrorBudget& b = a.budget;
    if (b.basis >= std::max(b.reduction, b.load) && f.model.terms < max_terms) {
      f.model.terms = std::min(max_terms, reference_terms(f.model.basis, f.model.terms));
    } else if (b.reduction >= b.load && vectors_free && 12 * f.reduction.vectors < sys.all_modes) {
      // Only while the budget's richer variant (twice as many again) stays a reduced model.
      f.reduction.vectors *= 2;
    } else {
      a.tolerance_met = false;
      break;
    }
  }
  a.model = f.model;
  a.reference_terms = reference_terms(f.model.basis, f.model.terms);
  a.reduction = f.reduction;
  a.load = f.load;
  a.stable = a.floquet.max_abs_multiplier <= 1 + std::max(a.budget.total(), 1e-9);
  return a;
}

}  // namespace bladestab
