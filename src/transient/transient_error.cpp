#include "bladestab/transient/transient_error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {

// The time-stepping error of a run, relative to its quantities; none for RKF45's fixed step (54),
// which holds no tolerance: its error is the stiffest mode's parasitic growth and the step's
// truncation, 4.7e-7 of the axial peak at 1/33 of that period (validation.md). The fast method's:
// its propagators' bound, or the self-check's difference beyond what the reference's own tolerance
// allows it (SelfCheck::reference_part: a feather touch's vibration is below the reference's
// resolution, and the difference then is the reference's).
std::optional<double> relative_method_error(const TransientResult& r, const TransientOptions& o) {
  if (r.method == TransientMethod::rkf45) return o.adaptive ? std::optional(o.tolerance) : std::nullopt;
  const double propagators = r.exact.contact_error * std::max(1, r.exact.contact_pieces);
  const double checked = r.self_check ? std::max(0.0, r.self_check->difference - r.self_check->reference_part) : 0.0;
  return std::max(propagators, checked);
}

// The peaks among the quantities: each the largest over the samples of a value per sample.
constexpr std::array<const char*, 4> peak_names{"peak_tip_lateral_m", "peak_tip_axial_change_m",
                                                "peak_vibration_energy_j", "peak_tip_axial_m"};

bool is_peak(const std::string& name) {
  return std::find(peak_names.begin(), peak_names.end(), name) != peak_names.end();
}

// The value per sample whose largest over the run is peak `name` (the vibration energy from the
// run's start: its initial vibration energy plus the change of the total).
double peak_sample(const std::string& name, const TransientResult& r, const TransientSample& s) {
  if (name == "peak_tip_lateral_m") return std::abs(s.tip_lateral_m);
  if (name == "peak_tip_axial_change_m") return std::abs(s.tip_axial_m - r.static_tip_axial_m);
  if (name == "peak_tip_axial_m") return std::abs(s.tip_axial_m);
  return r.initial_vibration_energy_j + s.total_energy_j - r.samples.front().total_energy_j;
}

// Peak `name` over each revolution of `r` (index: the whole revolutions before the sample; the
// start joins the first).
std::vector<double> revolution_peaks(const std::string& name, const TransientResult& r) {
  std::vector<double> peaks;
  for (const TransientSample& s : r.samples) {
    const std::size_t k = static_cast<std::size_t>(std::max(0.0, std::ceil(s.revolutions) - 1));
    if (peaks.size() <= k) peaks.resize(k + 1, -std::numeric_limits<double>::infinity());
    peaks[k] = std::max(peaks[k], peak_sample(name, r, s));
  }
  return peaks;
}

// The largest difference of two runs' peaks `name` revolution by revolution, over the revolutions
// both ran: it bounds the difference of their peaks, which may agree by chance where their
// revolutions' do not (the shipped scene's lateral peak over 60 revolutions: 8 and 12 terms 9.4e-7
// apart, their revolutions' peaks up to 1.4e-5, and 8 terms 5.5e-6 off 32).
double envelope_difference(const std::string& name, const TransientResult& a, const TransientResult& b) {
  const std::vector<double> x = revolution_peaks(name, a), y = revolution_peaks(name, b);
  double largest = 0;
  for (std::size_t k = 0; k < std::min(x.size(), y.size()); ++k) largest = std::max(largest, std::abs(x[k] - y[k]));
  return largest;
}

}  // namespace

std::vector<TransientQuantity> transient_quantities(const TransientResult& r) {
  std::vector<TransientQuantity> q;
  for (const char* name : peak_names) {
    const std::vector<double> peaks = revolution_peaks(name, r);
    q.push_back({name, peaks.empty() ? 0.0 : std::max(0.0, *std::max_element(peaks.begin(), peaks.end())), {}});
  }
  double mean = 0;
  for (const TransientSample& s : r.samples) mean += s.tip_axial_m / static_cast<double>(r.samples.size());
  q.insert(q.begin() + 3, {"mean_tip_axial_m", mean, {}});
  if (r.growth.omitted.empty()) q.push_back({"growth_per_revolution", r.growth.growth, {}});
  if (r.contact) {  // clearance mode: the casing's contacts, which the high modes shape
    q.push_back({"contact_closures", static_cast<double>(r.contact->closures), {}});
    q.push_back({"contact_time_s", r.contact->contact_time_s, {}});
    q.push_back({"contact_peak_force_n", r.contact->peak_force_n, {}});
    q.push_back({"contact_max_overlap_m", r.contact->max_overlap_m, {}});
  }
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

// Clearance mode's contacts are not linear: a time-stepping error grows through them (with friction,
// as a chaotic trajectory's), so that no step bound states it. There the method part is measured
// against the same run at 1/100 of its tolerances (a fixed step states none: unbounded already).
std::optional<TransientOptions> measured_method(const Scene& scene, const TransientOptions& o, double revolutions) {
  if (scene.load.mode != LoadMode::clearance || !o.adaptive) return std::nullopt;
  TransientOptions tighter = richer_options(o, revolutions);
  tighter.tolerance /= 100;
  tighter.contact_tolerance /= 100;
  return tighter;
}

// The richer runs' own error in quantity `name` (its values in them: `theirs`): their time stepping's
// (a fixed step's, unknown, leaves the quantity unbounded already: the richer runs share its options).
double richer_runs_error(const std::string& name, const std::vector<TransientResult>& references,
                         const std::vector<double>& theirs, const TransientOptions& o) {
  double own = 0;
  for (std::size_t k = 0; k < references.size(); ++k) {
    own += name == "growth_per_revolution" ? references[k].growth.error_estimate
                                           : relative_method_error(references[k], o).value_or(0) * std::abs(theirs[k]);
  }
  return own;
}

// The basis part of a quantity `f` = {this run's, the richer runs' values} on the `ladder` of their
// terms (the richest repeated where there is one richer model): the algebraic tail (basis_tail).
// Differences that do not contract (the richer pair's the larger, or of the other sign) show the
// models short of their asymptotic range: then at least the largest difference at the slowest
// trusted rate (the sine basis' mean axial deflection at 10, 20, 40 terms: −5.5e-9, then +2.3e-8).
// The tails are taken as factor × |difference|, not relative × |f|: a quantity the load does not
// excite (the lateral peak without Coriolis coupling) is 0 on every model, and its tail 0.
double basis_part(const std::vector<double>& f, const std::vector<int>& ladder) {
  const double d1 = f[0] - f[1], d2 = f[1] - f[2];
  const double tail = basis_tail(f, ladder, BasisConvergence::sine).factor * std::abs(d1);
  if (ladder[2] == ladder[1] || (std::abs(d2) < std::abs(d1) && d1 * d2 >= 0)) return tail;
  const double largest = std::max(std::abs(d1), std::abs(d2));
  const std::vector<int> capped{ladder[0], ladder[1], ladder[1]};
  return std::max(tail, basis_tail({f[1] + largest, f[1], f[1]}, capped, BasisConvergence::sine).factor * largest);
}

// Where a richer run left the small-deflection range before the run's end, the reason it bounds
// nothing.
std::string shorter_history(const TransientResult& r, const std::vector<TransientResult>& references) {
  const double ours_end = r.samples.empty() ? 0 : r.samples.back().revolutions;
  for (const TransientResult& reference : references) {
    const double theirs_end = reference.samples.empty() ? 0 : reference.samples.back().revolutions;
    if (reference.stopped && theirs_end < ours_end) {
      return fmt::format("basis: the richer model left the small-deflection range at revolution {:.4g}, before this "
                         "run's end at {:.4g}", theirs_end, ours_end);
    }
  }
  return {};
}

// The run `r` against the same runs on the richer models, whose own time-stepping errors join the
// basis part.
TransientErrorEstimate compare_with_richer(const TransientOptions& o, const TransientResult& r, int terms,
                                           const std::vector<int>& reference_terms,
                                           const std::vector<TransientResult>& references,
                                           const std::optional<TransientResult>& tighter) {
  TransientErrorEstimate estimate{reference_terms, transient_quantities(r)};
  const std::vector<TransientQuantity> tight = tighter ? transient_quantities(*tighter) : std::vector<TransientQuantity>{};
  std::vector<std::vector<TransientQuantity>> theirs;
  for (const TransientResult& reference : references) theirs.push_back(transient_quantities(reference));
  const std::optional<double> method = relative_method_error(r, o);
  const std::string shorter = shorter_history(r, references);
  // One richer model: the tail at the slowest trusted rate (basis_tail's richest model "capped",
  // n[2] = n[1]); two: at the rate they measure.
  const std::vector<int> ladder{terms, reference_terms.front(), reference_terms.back()};
  for (TransientQuantity& q : estimate.quantities) {
    if (!method) {
      q.budget.unbounded.push_back("method: the fixed step (--step fixed) states no error of its own");
    } else {
      q.budget.method = q.name == "growth_per_revolution" ? r.growth.error_estimate : *method * std::abs(q.value);
    }
    const auto measured = std::find_if(tight.begin(), tight.end(), [&](const TransientQuantity& x) { return x.name == q.name; });
    if (measured != tight.end()) q.budget.method = std::max(q.budget.method, std::abs(q.value - measured->value));
    if (!shorter.empty()) {
      q.budget.unbounded.push_back(shorter);
      continue;
    }
    std::vector<double> values;
    for (const std::vector<TransientQuantity>& t : theirs) {
      const auto match = std::find_if(t.begin(), t.end(), [&](const TransientQuantity& x) { return x.name == q.name; });
      if (match != t.end()) values.push_back(match->value);
    }
    if (values.size() != references.size()) {
      q.budget.unbounded.push_back("basis: the richer model reports no " + q.name);
      continue;
    }
    q.budget.basis = basis_part({q.value, values.front(), values.back()}, ladder) +
                     richer_runs_error(q.name, references, values, o);
    if (is_peak(q.name)) q.budget.basis = std::max(q.budget.basis, envelope_difference(q.name, r, references.front()));
  }
  return estimate;
}

// The revolutions a stopped run is compared over: to its stop.
double compared_revolutions(const TransientOptions& o, const TransientResult& r) {
  return r.stopped ? r.samples.back().revolutions : o.revolutions;
}

}  // namespace

std::vector<BladeModel> assemble_richer_models(const Scene& scene) {
  ModelSpec spec = scene.model;
  spec.terms = reference_terms(scene.model.basis, scene.model.terms);
  std::vector<BladeModel> richer{assemble_model(scene, spec)};
  const int rate_terms = reference_terms(scene.model.basis, spec.terms);
  if (scene.model.basis == BasisKind::sine && rate_terms > spec.terms) {
    spec.terms = rate_terms;
    richer.push_back(assemble_model(scene, spec));
  }
  return richer;
}

TransientErrorEstimate estimate_transient_error(const Scene& scene, const TransientOptions& o,
                                                const TransientResult& r) {
  std::vector<TransientResult> references;
  std::vector<int> terms;
  for (const BladeModel& m : assemble_richer_models(scene)) {
    references.push_back(run_transient(m, scene, richer_options(o, compared_revolutions(o, r))));
    terms.push_back(m.spec.terms);
  }
  std::optional<TransientResult> tighter;
  if (const auto t = measured_method(scene, o, compared_revolutions(o, r))) tighter = run_transient(assemble_model(scene), scene, *t);
  return compare_with_richer(o, r, scene.model.terms, terms, references, tighter);
}

EstimatedTransient run_transient_with_error(const BladeModel& model, const std::vector<BladeModel>& richer,
                                            const Scene& scene, const TransientOptions& o,
                                            const std::function<void(int, int)>& richer_progress) {
  Cancellation speculative;
  TransientOptions beside = richer_options(o, o.revolutions);
  beside.progress = [&speculative, &richer_progress](int done, int total) {
    if (speculative.cancelled()) throw WorkCancelled();
    if (richer_progress) richer_progress(done, total);
  };
  beside.contact_progress = beside.progress;
  // The richer models, then the same model at tighter tolerances where the method part is measured.
  const std::optional<TransientOptions> tight_beside = measured_method(scene, beside, o.revolutions);
  std::optional<WorkPool<TransientResult>> pool;
  pool.emplace(worker_threads(o.threads), richer.size() + (tight_beside ? 1 : 0),
               [&](std::size_t k) {
                 return k < richer.size() ? run_transient(richer[k], scene, beside) : run_transient(model, scene, *tight_beside);
               },
               &speculative);
  EstimatedTransient answer;
  try {
    answer.result = run_transient(model, scene, o);
  } catch (...) {
    speculative.cancel();
    throw;
  }
  if (answer.result.stopped) {
    speculative.cancel();
    pool.reset();  // waits for a running task to stop
  }
  TransientOptions to_stop = richer_options(o, compared_revolutions(o, answer.result));
  to_stop.progress = to_stop.contact_progress = richer_progress;
  std::vector<TransientResult> references;
  std::vector<int> terms;
  for (const BladeModel& m : richer) {
    terms.push_back(m.spec.terms);
    try {
      references.push_back(pool ? pool->get(references.size()) : run_transient(m, scene, to_stop));
    } catch (const std::exception& e) {
      speculative.cancel();
      answer.error_unavailable = fmt::format("the run on {} terms failed: {}", m.spec.terms, e.what());
      answer.work_limited = is_work_limit(e);
      return answer;
    }
  }
  std::optional<TransientResult> tighter;
  if (const auto t = measured_method(scene, to_stop, compared_revolutions(o, answer.result))) {
    try {
      tighter = pool ? pool->get(richer.size()) : run_transient(model, scene, *t);
    } catch (const std::exception& e) {
      speculative.cancel();
      answer.error_unavailable = fmt::format("the run at 1/100 of the tolerances failed: {}", e.what());
      answer.work_limited = is_work_limit(e);
      return answer;
    }
  }
  answer.error = compare_with_richer(o, answer.result, scene.model.terms, terms, references, tighter);
  return answer;
}

}  // namespace bladestab
