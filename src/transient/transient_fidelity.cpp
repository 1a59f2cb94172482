#include "bladestab/transient/transient_fidelity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/modal/basis_error.hpp"

namespace bladestab {
namespace {

// The quantity furthest above the tolerance, relative to its value (the growth: to max(1, |growth|)).
struct Shortfall {
  std::string name;
  double relative = 0, basis = 0;  // its whole error and basis part, relative
  std::string unbounded;           // why its error is not bounded
};

Shortfall worst_quantity(const TransientErrorEstimate& e) {
  Shortfall worst;
  for (const TransientQuantity& q : e.quantities) {
    const double scale = q.name == "growth_per_revolution" ? std::max(1.0, std::abs(q.value)) : std::abs(q.value);
    const double total = q.budget.total();
    const double relative = total == 0 ? 0 : scale > 0 ? total / scale : std::numeric_limits<double>::infinity();
    if (!q.budget.unbounded.empty()) return {q.name, std::numeric_limits<double>::infinity(), 0, q.budget.unbounded.front()};
    if (relative > worst.relative) worst = {q.name, relative, scale > 0 ? q.budget.basis / scale : relative, {}};
  }
  return worst;
}

// "tolerance ε: not met with N terms per field (<quantity> estimated e)".
std::string not_met(double tolerance, int terms, const Shortfall& worst) {
  return fmt::format("tolerance {}: not met with {} terms per field ({} estimated {:.2g})", tolerance, terms, worst.name,
                     worst.relative);
}

// Why the rounds end at `terms` with `worst` above `tolerance` (empty: raise). `stalled`: the raises
// in a row, this round's among them, that did not halve the basis part.
std::string why_not_raised(const Shortfall& worst, double tolerance, int terms, int stalled) {
  const std::string head = not_met(tolerance, terms, worst);
  if (!worst.unbounded.empty()) return fmt::format("{}: its error is not bounded ({})", head, worst.unbounded);
  if (worst.basis < worst.relative - worst.basis) {
    return fmt::format("{}: the time stepping's part is the larger; more terms do not lower it", head);
  }
  if (stalled >= 2) return fmt::format("{}: the last two raises did not halve its basis part", head);
  return {};
}

}  // namespace

EstimatedTransient run_transient_round(const TransientRoundModels& m, const Scene& scene,
                                       const std::function<void(int, int)>& richer_progress) {
  if (m.richer.empty()) return {run_transient(m.model, scene, m.options), std::nullopt, m.richer_unavailable};
  return run_transient_with_error(m.model, m.richer, scene, m.options, richer_progress);
}

TransientAtTolerance run_transient_to_tolerance(const Scene& scene, double tolerance, const TransientRoundBuilder& build,
                                                const std::function<void(int, int)>& richer_progress) {
  Scene round = scene;
  TransientRoundModels models = build(round);
  TransientAtTolerance answer{run_transient_round(models, round, richer_progress), models.model, true, {}};
  if (!answer.run.error) {
    answer.tolerance_met = false;
    answer.tolerance_unmet = fmt::format("tolerance {}: not known to be met without the error estimate ({})",
                                         tolerance, answer.run.error_unavailable);
    answer.work_limited = answer.run.work_limited;
    return answer;
  }
  double previous_basis = std::numeric_limits<double>::infinity();
  int stalled = 0;
  while (true) {
    const Shortfall worst = worst_quantity(*answer.run.error);
    if (worst.relative <= tolerance) return answer;
    answer.tolerance_met = false;
    stalled = worst.basis > 0.5 * previous_basis ? stalled + 1 : 0;
    answer.tolerance_unmet = why_not_raised(worst, tolerance, round.model.terms, stalled);
    if (!answer.tolerance_unmet.empty()) return answer;
    Scene next = round;
    next.model.terms = reference_terms(round.model.basis, round.model.terms);
    if (next.model.terms <= round.model.terms) {
      answer.tolerance_unmet = not_met(tolerance, round.model.terms, worst) + ", the most terms a model takes";
      return answer;
    }
    // A round that may not start, or ends without its estimate, leaves this one's answer standing.
    std::string stop;
    try {
      models = build(next);
      stop = models.richer.empty() ? models.richer_unavailable : "";
    } catch (const std::exception& e) {
      stop = e.what();
    }
    std::optional<EstimatedTransient> raised;
    bool work_limited = false;
    if (stop.empty()) {
      try {
        raised = run_transient_round(models, next, richer_progress);
        if (!raised->error) stop = raised->error_unavailable;
        work_limited = raised->work_limited;
      } catch (const NumericalError& e) {  // its own checks failed; a stop (Ctrl-C, a deadline) goes through
        stop = e.what();
        work_limited = is_work_limit(e);
      }
    }
    if (!stop.empty()) {
      answer.tolerance_unmet = fmt::format("{}; {} terms: {}", not_met(tolerance, round.model.terms, worst),
                                           next.model.terms, stop);
      answer.work_limited = work_limited;
      return answer;
    }
    answer = {std::move(*raised), models.model, true, {}};
    previous_basis = worst.basis;
    round = next;
  }
}

}  // namespace bladestab
