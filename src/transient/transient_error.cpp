#include "bladestab/transient/transient_error.hpp"

#include <algorithm>
#include <cmath>

#include "bladestab/modal/basis_error.hpp"

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
  double lateral = 0, axial = 0, energy = 0;
  const double start = r.samples.empty() ? 0 : r.samples.front().total_energy_j;
  for (const TransientSample& s : r.samples) {
    lateral = std::max(lateral, std::abs(s.tip_lateral_m));
    axial = std::max(axial, std::abs(s.tip_axial_m - r.static_tip_axial_m));
    energy = std::max(energy, r.initial_vibration_energy_j + s.total_energy_j - start);
  }
  std::vector<TransientQuantity> q{{"peak_tip_lateral_m", lateral, {}},
                                   {"peak_tip_axial_change_m", axial, {}},
                                   {"peak_vibration_energy_j", energy, {}}};
  if (r.growth.omitted.empty()) q.push_back({"growth_per_revolution", r.growth.growth, {}});
  return q;
}

TransientErrorEstimate estimate_transient_error(const Scene& scene, const TransientOptions& o,
                                                const TransientResult& r) {
  TransientErrorEstimate estimate;
  ModelSpec richer = scene.model;
  richer.terms = estimate.reference_terms = reference_terms(scene.model.basis, scene.model.terms);
  TransientOptions same = o;
  same.self_check = false;
  same.progress = nullptr;
  if (r.stopped) {
    // The same window: to the stop, and past it for the growth as the run itself.
    same.revolutions = r.samples.back().revolutions;
  }
  const TransientResult reference = run_transient(assemble_model(scene, richer), scene, same);
  std::vector<TransientQuantity> ours = transient_quantities(r), theirs = transient_quantities(reference);
  const double method = relative_method_error(r, o);
  const std::vector<int> terms{scene.model.terms, estimate.reference_terms, estimate.reference_terms};
  for (TransientQuantity& q : ours) {
    const auto match = std::find_if(theirs.begin(), theirs.end(), [&](const TransientQuantity& t) { return t.name == q.name; });
    if (match != theirs.end()) {
      // The response to a concentrated tip load converges algebraically in the basis: the
      // difference gets the algebraic tail at the slowest trusted rate (basis_tail's richest model
      // "capped": n[2] = n[1]).
      q.budget.basis = basis_tail({q.value, match->value, match->value}, terms, BasisConvergence::sine).relative * std::abs(match->value);
    } else {
      q.budget.unbounded.push_back("basis: the richer model reports no " + q.name);
    }
    q.budget.method = q.name == "growth_per_revolution" ? r.growth.error_estimate : method * std::abs(q.value);
  }
  estimate.quantities = std::move(ours);
  return estimate;
}

}  // namespace bladestab
