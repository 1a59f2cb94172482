#include "bladestab/transient/transient_error.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/modal/basis_error.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {

// The time-stepping error of a run, relative to its quantities.
double relative_method_error(const TransientResult& r, const TransientOptions& o) {
  if (r.method == TransientMethod::rkf45) return o.tolerance;
  const double propagators = r.exact.contact_error * std::max(1, r.exact.contact_pieces);
  return std::max(propagators, r.self_check ? r.self_check->difference : 0.0);
}

}  // namespace

std::vector<TransientQuantity> transient_quantities(const TransientResult& r) {
  double lateral = 0, axial = 0, energy = 0, mean = 0;
  const double start = r.samples.empty() ? 0 : r.samples.front().total_energy_j;
  for (const TransientSample& s : r.samples) {
    lateral = std::max(lateral, std::abs(s.tip_lateral_m));
    axial = std::max(axial, std::abs(s.tip_axial_m - r.static_tip_axial_m));
    energy = std::max(energy, r.initial_vibration_energy_j + s.total_energy_j - start);
    mean += s.tip_axial_m / static_cast<double>(r.samples.size());
  }
  std::vector<TransientQuantity> q{{"peak_tip_lateral_m", lateral, {}},
                                   {"peak_tip_axial_change_m", axial, {}},
                                   {"peak_vibration_energy_j", energy, {}},
                                   {"mean_tip_axial_m", mean, {}}};
  if (r.growth.omitted.empty()) q.push_back({"growth_per_revolution", r.growth.growth, {}});
  return q;
}

namespace {

// The richer model's options: the run's, without its self-check and progress; over `revolutions`.
TransientOptions richer_options(const TransientOptions& o, double revolutions) {
  TransientOptions same = o;
  same.self_check = false;
  same.progress = nullptr;
  same.contact_progress = nullptr;
  same.revolutions = revolutions;
  return same;
}

// The run `r` against the same run on the richer model, whose own time-stepping error joins the basis
// part.
TransientErrorEstimate compare_with_richer(const TransientOptions& o, const TransientResult& r, int terms,
                                           int reference_terms, const TransientResult& reference) {
  const double reference_method = relative_method_error(reference, o);
  TransientErrorEstimate estimate;
  estimate.reference_terms = reference_terms;
  std::vector<TransientQuantity> ours = transient_quantities(r), theirs = transient_quantities(reference);
  const double method = relative_method_error(r, o);
  // A richer run that left the small-deflection range earlier saw a shorter history: no bound.
  const double ours_end = r.samples.empty() ? 0 : r.samples.back().revolutions;
  const double theirs_end = reference.samples.empty() ? 0 : reference.samples.back().revolutions;
  const bool shorter = reference.stopped && theirs_end < ours_end;
  const std::vector<int> ladder{terms, reference_terms, reference_terms};
  for (TransientQuantity& q : ours) {
    const auto match = std::find_if(theirs.begin(), theirs.end(), [&](const TransientQuantity& t) { return t.name == q.name; });
    if (shorter) {
      q.budget.unbounded.push_back(fmt::format("basis: the richer model left the small-deflection range at revolution "
                                               "{:.4g}, before this run's end at {:.4g}", theirs_end, ours_end));
    } else if (match != theirs.end()) {
      // The response to a concentrated tip load converges algebraically in the basis: the
      // difference gets the algebraic tail at the slowest trusted rate (basis_tail's richest model
      // "capped": n[2] = n[1]).
      const double own = q.name == "growth_per_revolution" ? reference.growth.error_estimate
                                                           : reference_method * std::abs(match->value);
      q.budget.basis =
          basis_tail({q.value, match->value, match->value}, ladder, BasisConvergence::sine).relative * std::abs(match->value) +
          own;
    } else {
      q.budget.unbounded.push_back("basis: the richer model reports no " + q.name);
    }
    q.budget.method = q.name == "growth_per_revolution" ? r.growth.error_estimate : method * std::abs(q.value);
  }
  estimate.quantities = std::move(ours);
  return estimate;
}

// The revolutions a stopped run is compared over: to its stop.
double compared_revolutions(const TransientOptions& o, const TransientResult& r) {
  return r.stopped ? r.samples.back().revolutions : o.revolutions;
}

}  // namespace

ModelSpec richer_model_spec(const Scene& scene) {
  ModelSpec richer = scene.model;
  richer.terms = reference_terms(scene.model.basis, scene.model.terms);
  return richer;
}

TransientErrorEstimate estimate_transient_error(const Scene& scene, const TransientOptions& o,
                                                const TransientResult& r) {
  const ModelSpec richer = richer_model_spec(scene);
  const TransientResult reference =
      run_transient(assemble_model(scene, richer), scene, richer_options(o, compared_revolutions(o, r)));
  return compare_with_richer(o, r, scene.model.terms, richer.terms, reference);
}

EstimatedTransient run_transient_with_error(const BladeModel& model, const BladeModel& richer, const Scene& scene,
                                            const TransientOptions& o,
                                            const std::function<void(int, int)>& richer_progress) {
  const int richer_terms = richer.spec.terms;
  Cancellation speculative;
  TransientOptions beside = richer_options(o, o.revolutions);
  beside.progress = [&speculative, &richer_progress](int done, int total) {
    if (speculative.cancelled()) throw WorkCancelled();
    if (richer_progress) richer_progress(done, total);
  };
  beside.contact_progress = beside.progress;
  std::optional<WorkPool<TransientResult>> pool;
  pool.emplace(worker_threads(o.threads), 1, [&](std::size_t) { return run_transient(richer, scene, beside); }, &speculative);
  EstimatedTransient answer;
  try {
    answer.result = run_transient(model, scene, o);
  } catch (...) {
    speculative.cancel();
    throw;
  }
  try {
    TransientResult reference;
    if (answer.result.stopped) {
      speculative.cancel();
      pool.reset();  // waits for a running task to stop
      TransientOptions to_stop = richer_options(o, compared_revolutions(o, answer.result));
      to_stop.progress = to_stop.contact_progress = richer_progress;
      reference = run_transient(richer, scene, to_stop);
    } else {
      reference = pool->get(0);
    }
    answer.error = compare_with_richer(o, answer.result, scene.model.terms, richer_terms, reference);
  } catch (const std::exception& e) {
    answer.error_unavailable = fmt::format("the run on {} terms failed: {}", richer_terms, e.what());
  }
  return answer;
}

}  // namespace bladestab
