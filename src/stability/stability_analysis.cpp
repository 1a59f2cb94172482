#include "bladestab/stability/stability_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "bladestab/blade/damping.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/blade/reduction.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "bladestab/ltp/step_doubling.hpp"
#include "support/work_pool.hpp"

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
  return periodic_system(assemble_model(scene, f.model), scene, f.load, f.reduction);
}

// The multipliers of one fidelity: the true pulse train by its piecewise monodromy, a series by the
// requested method.
FloquetResult floquet_of(const Scene& scene, const Fidelity& f, const PeriodicSystem& sys, const FloquetOptions& o) {
  if (!f.load.exact_pulse) return floquet_multipliers(sys, o);
  if (o.method == FloquetMethod::hill || o.method == FloquetMethod::koopman_hill) {
    throw ParameterError("method", fmt::format("{}: Hill methods need a Fourier load; load.approximation = \"exact\" is "
                                               "integrated through each pulse (use monodromy or auto)",
                                               to_string(o.method)));
  }
  return pulse_train_multipliers(sys, periodic_pulse(pulse_train(scene)), o);
}

// max|ρ| of a variant and the error of that value.
struct VariantRho {
  double rho = 0, error = 0;
};

// max|ρ| of a variant of the scene's system and its error: Magnus levels from 1/16 of the count
// where h‖A‖ ≤ 2 (minimum_magnus_steps), doubled until StepDoubling accepts max|ρ| within `tol`.
// A variant independent of the answer runs beside it; the budget's `method` part counts the
// answer's own discretization once. Where the ladder does not settle within four levels or would
// pass max_magnus_steps, and for the exact train, the variant takes the monodromy's own refinement
// to `tol` (which refuses a period that needs more).
VariantRho variant_max_rho(const Scene& scene, const Fidelity& f, double tol, double max_flops,
                           const Cancellation& stop) {
  // Polled at every level: a variant of an answer that failed stops there (WorkCancelled).
  const auto poll = [&stop](int, int) {
    if (stop.cancelled()) throw WorkCancelled();
  };
  const PeriodicSystem sys = system_at(scene, f);
  const int safe = minimum_magnus_steps(sys), first = std::max(8, safe / 16);
  StepDoubling ladder(first, 8 * first, safe, monodromy_step_work(sys), max_flops);
  if (!f.load.exact_pulse && 8 * first <= max_magnus_steps && ladder.last() == 8 * first) {
    std::optional<double> previous;
    for (int steps = first; steps <= ladder.last(); steps *= 2) {
      poll(0, 0);
      const Eigen::MatrixXd phi = magnus_monodromy(sys, steps);
      if (!phi.allFinite()) break;
      const double rho = phi.eigenvalues().cwiseAbs().maxCoeff();
      if (previous) {
        const std::optional<double> error = ladder.judge(steps, std::abs(rho - *previous), tol * std::max(1.0, rho));
        if (error) return {rho, *error};
      }
      previous = rho;
    }
  }
  const FloquetResult r = floquet_of(scene, f, sys, {FloquetMethod::monodromy, 0, tol, false, poll, max_flops});
  return {r.max_abs_multiplier, r.error_estimate};
}

// The variants of the budget, each differing from `f` in one part only (`fidelities`), with the
// factors their differences are taken at.
struct VariantPlan {
  static constexpr std::size_t none = static_cast<std::size_t>(-1);
  std::vector<Fidelity> fidelities;
  std::size_t basis = none, reduction = none, load = none;
  // The sine basis only: the same terms in the Legendre basis (independent_basis_check).
  std::size_t other_basis = none;
  double basis_factor = 1, reduction_factor = 1;
};

// The sine basis's richer model shares its failure mode: its high modes converge like 1/N (its V_n
// force v'(0) = 0) and, under the true pulse train's broad spectrum, meet spurious tongues that
// persist as N doubles (the paper blade at Ω = 300 rad/s, F̄ = 5: max|ρ| = 1.0348 at 30 terms, 1.0408
// at 40, 1.0330 at 60, each within 2·|ρ_N − ρ_2N| of its richer model, while the Legendre basis gives
// 1 ± 2e-6 at 16–40 terms). The same terms in the Legendre basis share no mode with it: the basis part
// is at least their difference, with the margin of an exponentially converging comparison.
bool independent_basis_check(BasisKind basis) { return basis == BasisKind::sine; }

VariantPlan plan_variants(const Scene& scene, const Fidelity& f) {
  VariantPlan v;
  const auto add = [&v](Fidelity variant) {
    v.fidelities.push_back(std::move(variant));
    return v.fidelities.size() - 1;
  };
  if (f.reduction.kind == ReductionKind::automatic) {
    Fidelity richer = f;
    richer.reduction.vectors = 2 * f.reduction.vectors;
    // Galerkin projections do not converge monotonically in max|ρ|: a factor 2 of safety.
    v.reduction_factor = 2;
    v.reduction = add(richer);
  } else if (f.reduction.kind == ReductionKind::modal && f.reduction.cutoff_hz > 0) {
    Fidelity reduced = f;
    reduced.reduction = {ReductionKind::automatic, 2 * default_reduction_vectors, 0};
    v.reduction = add(reduced);
  }
  Fidelity richer_basis = f;
  richer_basis.model.terms = reference_terms(f.model.basis, f.model.terms);
  // Algebraic convergence: the difference to 2N understates the error up to 2× (sine basis), to
  // 1.5N up to 1.8× (a section table's kinks, basis_tail_factor).
  const BasisConvergence convergence = basis_convergence(scene.blade, f.model.basis, f.model.terms);
  v.basis_factor = convergence == BasisConvergence::exponential ? 1 : convergence == BasisConvergence::sine ? 2
                                                                      : basis_tail_factor(convergence);
  v.basis = add(richer_basis);
  if (independent_basis_check(f.model.basis)) {
    Fidelity other = f;
    other.model.basis = BasisKind::legendre;
    v.other_basis = add(other);
  }
  if (!f.load.cosine_approximation && !f.load.exact_pulse) {
    // The truncated series against the true pulse train it stands for.
    Fidelity exact = f;
    exact.load = exact_pulse_mean(pulse_train(scene));
    v.load = add(exact);
  }
  return v;
}

// The planned variants running: they do not depend on the answer, so they run beside it
// (WorkPool), the richer reduction first: its model is the largest. An answer that fails (its
// exception unwinding past the variants) cancels them: the running ones stop at their next level
// instead of finishing work nobody takes.
struct RunningVariants {
  RunningVariants() = default;
  RunningVariants(RunningVariants&&) = default;
  ~RunningVariants() {
    if (stop) stop->cancel();
  }
  std::unique_ptr<Cancellation> stop = std::make_unique<Cancellation>();
  std::unique_ptr<WorkPool<VariantRho>> tasks;
};

RunningVariants start_variants(const VariantPlan& plan, const Scene& scene, double tol, double max_flops,
                               int threads) {
  const double variant_tol = tol / 8;
  RunningVariants v;
  v.tasks = std::make_unique<WorkPool<VariantRho>>(
      threads, plan.fidelities.size(),
      [&scene, variant_tol, max_flops, variants = plan.fidelities, &stop = *v.stop](std::size_t i) {
        return variant_max_rho(scene, variants[i], variant_tol, max_flops, stop);
      });
  return v;
}

// The flops of building a round's systems at fidelity `f`: the answer's and its budget variants'.
double round_build_flops(const Scene& scene, const Fidelity& f, const VariantPlan& plan) {
  const bool two_planes = scene.blade.two_planes();
  double flops = periodic_system_flops(dof_layout(f.model, two_planes).size());
  for (const Fidelity& variant : plan.fidelities) {
    flops += periodic_system_flops(dof_layout(variant.model, two_planes).size());
  }
  return flops;
}

// Each part: factor · |ρ − ρ_variant| plus the variant's own error. `taken` after each variant.
ErrorBudget budget_of(const FloquetResult& r, const VariantPlan& plan, RunningVariants& running,
                      const std::function<void()>& taken) {
  const auto part = [&](std::size_t variant, double factor) {
    if (variant == VariantPlan::none) return 0.0;
    const VariantRho x = running.tasks->get(variant);
    taken();
    return factor * std::abs(r.max_abs_multiplier - x.rho) + x.error;
  };
  ErrorBudget b;
  b.method = r.error_estimate;
  b.basis = std::max(part(plan.basis, plan.basis_factor),
                     part(plan.other_basis, basis_tail_factor(BasisConvergence::exponential)));
  b.reduction = part(plan.reduction, plan.reduction_factor);
  b.load = part(plan.load, 1);
  return b;
}

// What fixes the reduction: the scene's cut-off or vectors, or, for vectors left to the program,
// the automatic reduction's richest level (its check, twice the vectors, would be the whole model).
std::string reduction_fixed_by(const ReductionSpec& r, bool vectors_free, int all_modes) {
  if (r.kind == ReductionKind::modal) return "the modal cut-off (--cutoff-hz or model.cutoff_hz)";
  if (!vectors_free) return "model.reduction_vectors";
  return fmt::format("the automatic reduction's richest level, {} vectors of {} modes (model.reduction = \"none\" "
                     "takes the whole model)", r.vectors, all_modes);
}

// The part of a budget above the tolerance that the analysis may not lower, in words.
std::string fixed_part(const ErrorBudget& b, double scale, const Fidelity& f, bool vectors_free, int all_modes) {
  if (b.reduction >= std::max(b.load, b.method)) {
    return fmt::format("its reduction part {:.2g} is fixed by {}", b.reduction / scale,
                       reduction_fixed_by(f.reduction, vectors_free, all_modes));
  }
  if (b.load >= b.method) {
    return fmt::format("its load part {:.2g} is fixed by the scene's load series (load.approximation)", b.load / scale);
  }
  return fmt::format("its method part {:.2g} did not come down", b.method / scale);
}

// The next round's fidelity: the largest part of the budget that the scene leaves free, raised; or,
// where none is or the basis part alone is beyond what more terms can reach (basis_can_reach: the
// sine basis and a section table converge algebraically; 10 sine terms toward 1e-6 ran for ten
// minutes, the fan blade's table at 250 rad/s, F̄ = 1.75 raised 16 terms to 81 and more for over a
// minute), why the tolerance is not met.
struct NextRound {
  std::optional<Fidelity> fidelity;
  std::string unmet;
};

NextRound next_round(const Scene& scene, const Fidelity& f, const StabilityAnswer& a, double tol, bool vectors_free) {
  const ErrorBudget& b = a.budget;
  const double scale = std::max(1.0, a.floquet.max_abs_multiplier), allowed = tol * scale;
  const bool basis_reachable = basis_can_reach(scene.blade, f.model, b.basis / scale, tol);
  Fidelity next = f;
  if (b.basis >= std::max(b.reduction, b.load) && basis_reachable) {
    next.model.terms = std::min(max_terms, reference_terms(f.model.basis, f.model.terms));
    return {next, {}};
  }
  if ((basis_reachable || b.basis <= allowed) && b.reduction >= b.load && vectors_free &&
      12 * f.reduction.vectors < a.full_size) {
    // Only while the budget's richer variant (twice as many again) stays a reduced model.
    next.reduction.vectors *= 2;
    return {next, {}};
  }
  if (b.basis > allowed && b.basis >= std::max(b.reduction, b.load)) {
    return {std::nullopt, tolerance_not_met(tol, f.model, b.total() / scale).what()};
  }
  return {std::nullopt, fmt::format("tolerance {}: not met (estimated error {:.2g}): {}", tol, b.total() / scale,
                                    fixed_part(b, scale, f, vectors_free, a.full_size))};
}

// A round whose reduction has twice the vectors of the round `before`: its reduction part (twice
// the change to twice the vectors again) holds the change from that round too, where the changes
// contracted by more than 16 at once. A projection's max|ρ| converges irregularly in its vectors:
// at Ω = 10 rad/s under the true train 3 → 6 vectors change it by 7e-5, 6 → 12 by 3.7e-7 (95×), and
// 6 and 12 are both 4.2e-5 off the whole model; the damped fan blade (ζ = 1 %, 300 rad/s, 81 terms)
// changes by 2.3e-5 from 24 to 48 vectors and by 8e-7 from 48 to 96 (29×), and 48 are 2.6e-5 off
// every richer model. At F̄ = 50 the changes 4.8e23 and 1.7e22 (28×) are real (6 vectors are 1.8e22
// off): held, its estimate is 28× its error.
void hold_irregular_reduction(StabilityAnswer& a, const StabilityAnswer& before) {
  const double change = std::abs(a.floquet.max_abs_multiplier - before.floquet.max_abs_multiplier);
  if (change > 8 * a.budget.reduction) a.budget.reduction = 2 * change;
}

// Adds `flops` of systems to `built`, the analysis's so far; past `limit`, its share of the work
// (StabilityRequest::work_flops), the analysis ends before building them.
void charge_systems(double& built, double flops, double limit, int terms) {
  built += flops;
  if (built > limit) {
    throw WorkLimitError(fmt::format("the stability analysis's systems ({} terms per field and its error budget's "
                                     "variants) would take {:.2g} flops, past its share {:.2g} of the work limit",
                                     terms, built, limit));
  }
}

// The first round's fidelity: the scene's, with the reduction's vectors chosen; the true train on
// the whole Ritz model where true_train_on_whole_model says so. That check's system is charged to
// `built`.
Fidelity first_fidelity(const Scene& scene, bool vectors_free, double& built, double limit) {
  Fidelity f{scene.model, scene.model.reduction, load_series(scene)};
  if (!f.load.frequency_known) {
    throw InputError("operation.speed_rad_s = 0: the pulses have no frequency; give load.pulse_frequency_hz "
                     "(in Hz, > 0) or a speed > 0");
  }
  if (vectors_free && f.load.exact_pulse) {
    charge_systems(built, periodic_system_flops(dof_layout(f.model, scene.blade.two_planes()).size()), limit,
                   f.model.terms);
    const PeriodicSystem whole = system_at(scene, {f.model, {ReductionKind::none, 0, 0}, f.load});
    if (true_train_on_whole_model(whole, pulse_train(scene))) f.reduction.kind = ReductionKind::none;
  }
  if (f.reduction.kind == ReductionKind::automatic && f.reduction.vectors == 0) {
    f.reduction.vectors = default_reduction_vectors;
  }
  return f;
}

// "N terms per field", and "and V reduction vectors" where the reduction is automatic.
std::string fidelity_text(const Fidelity& f) {
  if (f.reduction.kind != ReductionKind::automatic) return fmt::format("{} terms per field", f.model.terms);
  return fmt::format("{} terms per field and {} reduction vectors", f.model.terms, f.reduction.vectors);
}

// One fidelity round: the answer at `f` and its budget. The variants of `plan` start beside the
// answer once its first refinement level is done (or it is), so that an answer whose ladder the work
// limit refuses outright ends the round at once, not after a richer variant's first level. `done`
// counts the progress steps over every round (StabilityRequest::progress).
StabilityAnswer run_round(const Scene& scene, const Fidelity& f, const VariantPlan& plan,
                          const StabilityRequest& request, double ladder_flops, int& done) {
  std::optional<RunningVariants> variants;
  const auto start = [&] {
    if (!variants) variants.emplace(start_variants(plan, scene, request.tolerance, ladder_flops, request.threads));
  };
  const int variant_count = static_cast<int>(plan.fidelities.size());
  FloquetOptions options{request.method, request.harmonics, request.tolerance / 4, true, {}, ladder_flops};
  int levels = 0;
  options.progress = [&](int d, int total) {
    start();
    levels = d;
    if (request.progress) request.progress(done + d, done + total + variant_count);
  };
  const PeriodicSystem sys = system_at(scene, f);
  StabilityAnswer a;
  a.floquet = floquet_of(scene, f, sys, options);
  start();
  done += levels;
  int variants_left = variant_count;
  a.budget = budget_of(a.floquet, plan, *variants, [&] {
    ++done, --variants_left;
    if (request.progress) request.progress(done, done + variants_left);
  });
  a.reduced_size = sys.kept_modes;
  a.full_size = sys.all_modes;
  a.theta_rad_s = sys.angular_frequency;
  return a;
}

}  // namespace

bool verdict_decided(const StabilityAnswer& a) {
  const double rho = a.floquet.max_abs_multiplier, error = a.budget.total();
  return rho > 1 + error || rho + error <= 1 + 1e-9;
}

// Rounds from the scene's fidelity, raised while the budget exceeds the tolerance (next_round). A
// raised round that cannot finish (its ladders past the work limit, a check of its own failed)
// leaves the last finished round's answer standing, with the reason the tolerance is not met.
StabilityAnswer analyse_stability(const Scene& scene, const StabilityRequest& request) {
  refuse_impulse_jump(scene);
  const bool vectors_free = scene.model.reduction.kind == ReductionKind::automatic && scene.model.reduction.vectors == 0;
  const double tol = request.tolerance, ladder_flops = request.work_flops / 4, build_flops = request.work_flops / 4;
  double built = 0;  // the systems' flops so far (periodic_system_flops)
  Fidelity f = first_fidelity(scene, vectors_free, built, build_flops);
  VariantPlan plan = plan_variants(scene, f);
  charge_systems(built, round_build_flops(scene, f, plan), build_flops, f.model.terms);
  int done = 0;  // progress over the rounds: the answer's levels, then its variants
  StabilityAnswer a = run_round(scene, f, plan, request, ladder_flops, done);
  while (true) {
    const double relative = a.budget.total() / std::max(1.0, a.floquet.max_abs_multiplier);
    if (relative <= tol) break;
    a.tolerance_met = false;
    if (request.verdict_only && verdict_decided(a)) {
      a.tolerance_unmet =
          fmt::format("tolerance {}: not sought past the verdict, decided at estimated error {:.2g}", tol, relative);
      break;
    }
    const NextRound next = next_round(scene, f, a, tol, vectors_free);
    if (!next.fidelity) {
      a.tolerance_unmet = next.unmet;
      break;
    }
    const std::string raising = fmt::format("tolerance {}: not met (estimated error {:.2g}): raising it to {}", tol,
                                            relative, fidelity_text(*next.fidelity));
    VariantPlan next_plan = plan_variants(scene, *next.fidelity);
    const double next_built = built + round_build_flops(scene, *next.fidelity, next_plan);
    if (next_built > build_flops) {
      a.work_limited = true;
      a.tolerance_unmet = raising + " would pass the work limit";
      break;
    }
    try {
      const StabilityAnswer before = a;
      a = run_round(scene, *next.fidelity, next_plan, request, ladder_flops, done);
      if (next.fidelity->reduction.vectors > f.reduction.vectors) hold_irregular_reduction(a, before);
    } catch (const NumericalError& e) {
      a.work_limited = is_work_limit(e);
      a.tolerance_unmet = fmt::format("{} did not finish: {}", raising, e.what());
      break;
    }
    built = next_built;
    f = *next.fidelity;
    plan = std::move(next_plan);
  }
  a.model = f.model;
  a.reference_terms = reference_terms(f.model.basis, f.model.terms);
  a.reduction = f.reduction;
  a.load = f.load;
  // An estimate as large as max|ρ| itself leaves no digit of it known, and no verdict: a blade
  // whose growth over a period overflows the budget's models (F̄ far past buckling) lands here.
  if (!(a.budget.total() < a.floquet.max_abs_multiplier)) {
    throw NumericalError(fmt::format("the error estimate {:.2g} of max|ρ| = {:.6g} is as large as max|ρ| itself: no "
                                     "digit of it, and no verdict, is known with this model",
                                     a.budget.total(), a.floquet.max_abs_multiplier));
  }
  a.stable = a.floquet.max_abs_multiplier <= 1 + std::max(a.budget.total(), 1e-9);
  if (request.progress) request.progress(done, done);
  return a;
}

}  // namespace bladestab
