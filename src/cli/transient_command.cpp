// bladestab transient SCENE: time response to the rub, CSV of the history, JSON summary, chart.

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "support/message_text.hpp"
#include "bladestab/transient/response_analysis.hpp"
#include "bladestab/transient/transient.hpp"
#include "bladestab/transient/transient_checks.hpp"
#include "bladestab/transient/transient_error.hpp"
#include "bladestab/transient/transient_fidelity.hpp"
#include "chart.hpp"
#include "commands.hpp"
#include "embedding.hpp"
#include "json_output.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "notes.hpp"
#include "output_files.hpp"
#include "progress.hpp"
#include "transient_output.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

// Column of the history.
template <class Field>
std::vector<double> column(const TransientResult& r, Field field) {
  std::vector<double> out;
  out.reserve(r.samples.size());
  for (const TransientSample& s : r.samples) out.push_back(s.*field);
  return out;
}

// A value, or null where there is none.
Json optional_json(const std::optional<double>& value) { return value ? Json(*value) : Json(nullptr); }

TransientSummary summarize(const TransientResult& r, double sample_rate) {
  TransientSummary s;
  const std::vector<double> lat = column(r, &TransientSample::tip_lateral_m),
                            ax = column(r, &TransientSample::tip_axial_m);
  if (lat.size() >= 4) {
    s.lateral = amplitude_spectrum(lat, sample_rate);
    s.axial = amplitude_spectrum(ax, sample_rate);
    s.lateral_hz = dominant_frequency(s.lateral);
    s.axial_hz = dominant_frequency(s.axial);
  }
  for (std::size_t k = 0; k < lat.size(); ++k) {
    s.peak_lateral_m = std::max(s.peak_lateral_m, std::abs(lat[k]));
    s.peak_axial_m = std::max(s.peak_axial_m, std::abs(ax[k]));
    s.mean_axial_m += ax[k] / ax.size();
  }
  s.sample_rate_hz = sample_rate;
  s.sampling = peak_sampling(s);
  s.checks = check_transient(r);
  return s;
}

// The run's numbers as its files print them (printed_digits.hpp). An adaptive run holds each step's
// error to --tolerance of the state: a series is printed to that fraction of its largest value, any
// other number of the response to that fraction of itself. A fixed-step run states no error: its
// numbers get 6 digits.
class PrintedRun {
public:
  PrintedRun(const PrintedDigits& digits, std::optional<double> tolerance) : digits(digits), tolerance_(tolerance) {}
  double value(double v) const { return tolerance_ ? digits.relative(v, *tolerance_) : digits.unestimated(v); }
  std::vector<double> series(const std::vector<double>& values) const {
    double peak = 0;
    for (const double v : values) peak = std::max(peak, std::abs(v));
    return tolerance_ ? digits.absolute(values, digits.estimate(*tolerance_) * peak) : digits.unestimated(values);
  }
  const PrintedDigits& digits;

private:
  std::optional<double> tolerance_;
};

// The samples' times and revolutions are the output grid's, as they are; the energy balance's error,
// the contact propagators' bound and the self-check's measures are checks (2 digits, rounded up);
// the step sizes (no estimate of their own) get 6 digits.
TransientResult as_printed(TransientResult r, const PrintedRun& shown) {
  using Field = double TransientSample::*;
  for (const Field f : {&TransientSample::tip_lateral_m, &TransientSample::tip_axial_m,
                        &TransientSample::tip_lateral_velocity_m_s, &TransientSample::tip_axial_velocity_m_s,
                        &TransientSample::axial_force_n, &TransientSample::friction_force_n,
                        &TransientSample::casing_overlap_m, &TransientSample::strain_energy_j,
                        &TransientSample::kinetic_energy_j, &TransientSample::total_energy_j, &TransientSample::work_j}) {
    const std::vector<double> printed = shown.series(column(r, f));
    for (std::size_t k = 0; k < r.samples.size(); ++k) r.samples[k].*f = printed[k];
  }
  for (TransientSample& s : r.samples) s.energy_balance_error_j = shown.digits.measure(s.energy_balance_error_j);
  r.static_tip_axial_m = shown.value(r.static_tip_axial_m);
  if (r.growth.omitted.empty()) {
    r.growth.standard_error = shown.digits.estimate(r.growth.standard_error);
    r.growth.growth = shown.digits.absolute(r.growth.growth, r.growth.growth * r.growth.standard_error);
  }
  if (r.contact) {
    r.contact->stiffness_n_m = shown.digits.unestimated(r.contact->stiffness_n_m);
    r.contact->contact_time_s = shown.value(r.contact->contact_time_s);
    r.contact->peak_force_n = shown.value(r.contact->peak_force_n);
    r.contact->max_overlap_m = shown.value(r.contact->max_overlap_m);
  }
  r.exact.contact_error = shown.digits.measure(r.exact.contact_error);
  if (r.self_check) {
    r.self_check->difference = shown.digits.measure(r.self_check->difference);
    r.self_check->allowed = shown.digits.measure(r.self_check->allowed);
    r.self_check->reference_part = shown.digits.measure(r.self_check->reference_part);
  }
  r.steps.smallest_step = shown.digits.unestimated(r.steps.smallest_step);
  r.steps.largest_step = shown.digits.unestimated(r.steps.largest_step);
  r.fixed.step_s = shown.digits.unestimated(r.fixed.step_s);
  r.fixed.parasitic_growth = shown.digits.unestimated(r.fixed.parasitic_growth);
  return r;
}

// The numbers the estimate covers, to the digits their whole error supports (raw: as computed): the
// tip peaks and mean, the vibration energy (to the relative error of its peak), the growth.
void with_whole_error(TransientResult& r, TransientSummary& s, const TransientResult& raw_result, const TransientSummary& raw,
                      const std::optional<TransientErrorEstimate>& e, const PrintedDigits& digits) {
  if (const TransientQuantity* q = estimated(e, "peak_tip_lateral_m")) {
    s.peak_lateral_m = digits.absolute(raw.peak_lateral_m, q->budget.total());
  }
  if (const TransientQuantity* q = estimated(e, "peak_tip_axial_m")) {
    s.peak_axial_m = digits.absolute(raw.peak_axial_m, q->budget.total());
  }
  if (const TransientQuantity* q = estimated(e, "mean_tip_axial_m")) {
    s.mean_axial_m = digits.absolute(raw.mean_axial_m, q->budget.total());
  }
  if (const TransientQuantity* q = estimated(e, "peak_vibration_energy_j"); q && q->value > 0) {
    const double relative = q->budget.total() / q->value;
    s.checks.vibration_energy_j = digits.absolute(raw.checks.vibration_energy_j, relative * raw.checks.vibration_energy_j);
  }
  if (const TransientQuantity* q = estimated(e, "growth_per_revolution")) {
    r.growth.growth = digits.absolute(raw_result.growth.growth, q->budget.total());
    r.growth.error_estimate = digits.measure(q->budget.total());
  }
  if (!r.contact) return;
  using Field = double ContactSummary::*;
  for (const auto& [name, field] : {std::pair<const char*, Field>{"contact_time_s", &ContactSummary::contact_time_s},
                                    {"contact_peak_force_n", &ContactSummary::peak_force_n},
                                    {"contact_max_overlap_m", &ContactSummary::max_overlap_m}}) {
    if (const TransientQuantity* q = estimated(e, name)) {
      (*r.contact).*field = digits.absolute((*raw_result.contact).*field, q->budget.total());
    }
  }
}

// The spectra and peaks like the series they come from; the dominant frequencies, interpolated
// between the spectrum's bins, to 6 digits.
TransientSummary as_printed(TransientSummary s, const PrintedRun& shown) {
  s.lateral.amplitude = shown.series(s.lateral.amplitude);
  s.axial.amplitude = shown.series(s.axial.amplitude);
  if (s.lateral_hz) s.lateral_hz = shown.digits.unestimated(*s.lateral_hz);
  if (s.axial_hz) s.axial_hz = shown.digits.unestimated(*s.axial_hz);
  s.peak_lateral_m = shown.value(s.peak_lateral_m);
  s.peak_axial_m = shown.value(s.peak_axial_m);
  s.mean_axial_m = shown.value(s.mean_axial_m);
  s.checks.energy_error_j = shown.digits.measure(s.checks.energy_error_j);
  s.checks.energy_rounding_j = shown.digits.measure(s.checks.energy_rounding_j);
  if (s.sampling) {
    s.sampling->frequency_hz = shown.digits.unestimated(s.sampling->frequency_hz);
    s.sampling->samples_per_period = shown.digits.unestimated(s.sampling->samples_per_period);
    s.sampling->peak_bound = shown.digits.measure(s.sampling->peak_bound);
  }
  s.checks.vibration_energy_j = shown.value(s.checks.vibration_energy_j);
  return s;
}

std::string history_csv(const TransientResult& r) {
  std::string csv =
      "time_s,revolutions,tip_lateral_m,tip_axial_m,tip_lateral_velocity_m_s,tip_axial_velocity_m_s,"
      "axial_force_n,friction_force_n,casing_overlap_m,strain_energy_j,kinetic_energy_j,total_energy_j,work_j,"
      "energy_balance_error_j\n";
  for (const TransientSample& s : r.samples) {
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", s.time_s, s.revolutions, s.tip_lateral_m,
                       s.tip_axial_m, s.tip_lateral_velocity_m_s, s.tip_axial_velocity_m_s, s.axial_force_n,
                       s.friction_force_n, s.casing_overlap_m, s.strain_energy_j, s.kinetic_energy_j, s.total_energy_j,
                       s.work_j, s.energy_balance_error_j);
  }
  return csv;
}

// How the run was integrated, and whether it stopped.
void method_fields(Json& json, const TransientResult& r) {
  json["method"] = r.method == TransientMethod::fast ? "fast" : "rkf45";
  if (!r.fallback.empty()) json["method_fallback"] = r.fallback;
  if (r.method == TransientMethod::fast) {
    const ExactSteppingStatistics& e = r.exact;
    json["exact_stepping"] = {{"contact_pieces", e.contact_pieces}, {"magnus_steps", e.magnus_steps},
                              {"free_flight_exponentials", e.free_exponentials}, {"intervals", e.intervals},
                              {"contact_propagator_error", e.contact_error}};
    if (r.contact) {  // clearance mode: the casing contacts by RKF78
      json["contact_steps"] = {{"accepted", r.steps.accepted}, {"rejected", r.steps.rejected},
                               {"rhs_evaluations", r.steps.evaluations}, {"event_landings", r.steps.event_landings}};
    }
  }
  if (const std::optional<SelfCheck>& c = r.self_check) {
    json["self_check"] = {{"until_revolution", c->until_revolutions}, {"reference", c->reference},
                          {"reference_tolerance", c->reference_tolerance},
                          {"relative_difference", c->difference}, {"allowed", c->allowed},
                          {"relative_to", c->relative_to_resolution ? "reference_resolution" : "vibration"},
                          {"reference_part", c->reference_part}};
  }
  if (r.stopped) json["stopped"] = {{"revolution", r.stopped->revolution}, {"reason", r.stopped->reason}};
}

void summary_fields(Json& json, const TransientResult& r, const TransientSummary& s, bool adaptive) {
  method_fields(json, r);
  json["dominant_frequency_hz"] = {{"tip_lateral", optional_json(s.lateral_hz)}, {"tip_axial", optional_json(s.axial_hz)}};
  json["peak_tip_lateral_m"] = s.peak_lateral_m;
  json["peak_tip_axial_m"] = s.peak_axial_m;
  json["mean_tip_axial_m"] = s.mean_axial_m;
  json["static_tip_axial_m"] = r.static_tip_axial_m;
  if (const std::optional<PeakSampling>& p = s.sampling) {
    json["peak_sampling"] = {{"dominant_frequency_hz", p->frequency_hz}, {"samples_per_period", p->samples_per_period},
                             {"peak_between_samples_bound", std::isfinite(p->peak_bound) ? Json(p->peak_bound) : Json(nullptr)}};
  }
  if (r.growth.omitted.empty()) {
    json["growth_per_revolution"] = r.growth.growth;
    json["growth_per_revolution_ln_standard_error"] = r.growth.standard_error;
    json["growth_per_revolution_error_estimate"] = r.growth.error_estimate;
    if (!r.continued_log_change.empty()) json["growth_continued_revolutions"] = r.continued_log_change.size();
  } else {
    json["growth_per_revolution"] = nullptr;
    json["growth_per_revolution_omitted"] = r.growth.omitted;
  }
  const std::string unchecked = energy_balance_unchecked(r);
  json["energy_balance"] = {{"max_error_j", unchecked.empty() ? Json(s.checks.energy_error_j) : Json(nullptr)},
                            {"vibration_energy_j", s.checks.vibration_energy_j},
                            {"allowed_fraction", TransientChecks::max_energy_error},
                            {"allowed_rounding_j", s.checks.energy_rounding_j},
                            {"unchecked", unchecked.empty() ? Json(nullptr) : Json(unchecked)}};
  if (r.method == TransientMethod::rkf45) json["steps"] = {{"mode", adaptive ? "adaptive" : "fixed"},
                   {"accepted", r.steps.accepted},
                   {"rejected", r.steps.rejected},
                   {"rhs_evaluations", r.steps.evaluations},
                   {"smallest_s", r.steps.smallest_step},
                   {"largest_s", r.steps.largest_step},
                   {"event_landings", r.steps.event_landings},
                   {adaptive ? "step_cap_s" : "fixed_step_s", r.fixed.step_s},
                   {"steps_per_stiffest_period", r.fixed.steps_per_period},
                   {"parasitic_growth_of_stiffest_mode", r.fixed.parasitic_growth}};
  if (r.contact) {
    json["casing_contact"] = {{"penalty_stiffness_n_m", r.contact->stiffness_n_m},
                              {"closures", r.contact->closures},
                              {"contact_time_s", r.contact->contact_time_s},
                              {"peak_force_n", r.contact->peak_force_n},
                              {"max_overlap_m", r.contact->max_overlap_m}};
  }
}

// JSON error_estimate (each quantity's whole estimate) and error_budget (its parts, the value to the
// digits its estimate supports), or error_unavailable (why there is none).
void error_fields(Json& json, const std::optional<TransientErrorEstimate>& e, const std::string& unavailable,
                  const PrintedDigits& digits) {
  if (!e) {
    if (!unavailable.empty()) json["error_unavailable"] = unavailable;
    return;
  }
  json["error_reference_terms"] = e->reference_terms.front();
  if (e->reference_terms.size() > 1) json["error_rate_reference_terms"] = e->reference_terms.back();
  for (const TransientQuantity& q : e->quantities) {
    const double total = q.budget.total();
    // A quantity with an unbounded part has no estimate: null, and its budget says why.
    json["error_estimate"][q.name] = q.budget.unbounded.empty() ? Json(digits.measure(total)) : Json(nullptr);
    json["error_budget"][q.name] = {{"value", digits.absolute(q.value, total)},
                                    {"basis", digits.measure(q.budget.basis)},
                                    {"reduction", q.budget.reduction},
                                    {"load", q.budget.load},
                                    {"method", digits.measure(q.budget.method)},
                                    {"unbounded", q.budget.unbounded}};
  }
}

std::string summary_json(const Scene& scene, const BladeModel& model, const TransientResult& r, const TransientSummary& s,
                         bool adaptive, bool with_series, const PrintedError& error) {
  Json json;
  json["title"] = fmt::format("{} — {}", scene_title(scene), load_description(scene));
  json["scene"] = scene.source;
  json["model"] = describe_model(model);
  json["speed_rad_s"] = scene.operation.speed_rad_s;
  json["revolutions_run"] = r.samples.back().revolutions;
  summary_fields(json, r, s, adaptive);
  error_fields(json, error.estimate, error.unavailable, error.digits);
  if (error.tolerance) {
    json["tolerance"] = *error.tolerance;
    json["tolerance_met"] = error.tolerance_unmet.empty();
    json["tolerance_unmet"] = error.tolerance_unmet.empty() ? Json(nullptr) : Json("--" + error.tolerance_unmet);
  }
  if (with_series) {  // what the chart draws
    json["revolutions"] = column(r, &TransientSample::revolutions);
    json["tip_lateral_m"] = column(r, &TransientSample::tip_lateral_m);
    json["tip_axial_m"] = column(r, &TransientSample::tip_axial_m);
    json["tip_axial_velocity_m_s"] = column(r, &TransientSample::tip_axial_velocity_m_s);
    json["axial_force_n"] = column(r, &TransientSample::axial_force_n);
    json["spectrum"] = {
        {"frequency_hz", s.lateral.frequency_hz}, {"lateral", s.lateral.amplitude}, {"axial", s.axial.amplitude}};
    json["dominant"] = {{"lateral_hz", optional_json(s.lateral_hz)}, {"axial_hz", optional_json(s.axial_hz)}};
  }
  return json_text(json);
}

// The run's work before it starts: RKF45 never steps beyond the cap of the stiffest mode
// (transient.hpp): duration/cap steps (adaptive runs take up to twice as many, each cheaper than
// rkf45_seconds assumes); the history holds samples-per-rev × revolutions samples.
// The fast method: the distinct contact pieces of one revolution at half a Magnus step per RKF45
// step (their step doubling takes 0.31 at 16 terms and 0.27 at 24, t̄c = 0.01 and 0.5), and a
// propagator product per sample and pulse edge; in clearance mode every revolution's contact
// windows at most, by RKF78 (13 right-hand sides a step against RKF45's 6). An upper bound: at 16
// terms, t̄c = 0.5, 10 revolutions, 39 s against 6.5 s measured on one core; at 24 terms 5 min
// against 41 s. `share`
// scales it for a run whose refusal loses less than the answer (the richer run of the estimate).
// `spent`: the estimates of the rounds before (transient_fidelity.hpp), which the limits cover too.
// Returns this run's estimate (× share).
double check_transient_work(const BladeModel& model, const Scene& scene, const TransientOptions& o, double share = 1,
                            double spent = 0) {
  const double revolution = two_pi / scene.operation.speed_rad_s, duration = o.revolutions * revolution;
  const FixedStep step = transient_step(model, scene, o, duration);
  const bool fast = o.method == TransientMethod::fast && !o.follower && o.adaptive;
  // In force mode, pulses that meet the samples alike (samples a multiple of the pulses a revolution)
  // share their contact pieces: one pulse's contact is integrated (5 pulses on 32 terms: 1984 Magnus
  // steps). In clearance mode every contact is.
  const bool clearance = scene.load.mode == LoadMode::clearance;
  const bool alike = !clearance && !scene.load.pulse_frequency_hz &&
                     o.samples_per_revolution % scene.load.pulses_per_rev == 0;
  const double contact = std::min(1.0, scene.load.contact_time_rev * (alike ? 1 : scene.load.pulses_per_rev)) *
                         revolution * (clearance ? o.revolutions : 1.0);
  const double steps = !fast ? duration / step.step_s : contact / step.step_s / (clearance ? 1 : 2);
  const int dofs = model.layout.size();
  const double intervals = o.revolutions * (o.samples_per_revolution + 2.0 * scene.load.pulses_per_rev);
  const double seconds = !fast       ? rkf45_seconds(steps, dofs)
                         : clearance ? rkf45_seconds(steps * 13 / 6, dofs) + fast_transient_seconds(0, intervals, dofs)
                                     : fast_transient_seconds(steps, intervals, dofs);
  const double bytes = transient_history_bytes(o.revolutions, o.samples_per_revolution);
  check_work(fmt::format("--revolutions {:g} with model.terms = {}", o.revolutions, model.spec.terms),
             fmt::format("{:.3g} {} steps of a {}-dof model and {:.3g} samples{}", steps,
                         fast ? (clearance ? "RKF78" : "Magnus") : "RKF45", dofs,
                         o.revolutions * o.samples_per_revolution, spent > 0 ? ", after the rounds before," : ""),
             spent + share * seconds, bytes);
  return share * seconds;
}

// The richer models of the whole-error estimate (assemble_richer_models), or none where they cannot
// be built or their runs would pass the work limits (with `spent`, the rounds before): `why_not`
// then says so, else `work` is their estimate as charged. A refusal only leaves out the estimate,
// and the richer run goes beside the answer on a second core, so half the upper bound is compared
// with the limits (still about 3× the measured times at 16 and 24 terms; less would let a run with
// a slow richer model start and end at --max-seconds with nothing written: 13 pulses a revolution
// take 85 s, their answer alone 4.3 s); a richer run slower than that ends at --max-seconds like
// any run.
std::vector<BladeModel> checked_richer_models(const Scene& scene, const TransientOptions& o, double spent,
                                              std::string& why_not, double& work) {
  try {
    std::vector<BladeModel> richer = assemble_richer_models(scene);
    for (const BladeModel& m : richer) work += check_transient_work(m, scene, o, 0.5, spent + work);
    return richer;
  } catch (const InputError& e) {
    why_not = fmt::format("{}; --no-error-estimate leaves it out", e.what());
    work = 0;
    return {};
  }
}

// A run whose own checks failed (the integration, or a response that outgrew the model without
// stopping at the small-deflection range) is a numerical failure, exit 1: no files, no numbers.
void refuse_failed_run(const TransientSummary& s, const TransientResult& r, const TransientOptions& o, double tolerance,
                       double revolutions, double length) {
  const auto failure = transient_failure(s.checks, length);
  if (!failure || (!failure->integration && r.stopped)) return;
  const std::string what = o.adaptive ? fmt::format("--tolerance {:g}", tolerance)
                                      : fmt::format("--step fixed, {} steps per stiffest period", r.fixed.steps_per_period);
  const std::string advice =
      failure->integration ? (o.adaptive ? "use a smaller --tolerance"
                                         : "leave out --steps-per-period (the default keeps the step stable)")
      : r.growth.omitted.empty()
          ? fmt::format("the response grows ×{:.6g} per revolution: run fewer --revolutions or a smaller load", r.growth.growth)
          : "the response outgrows the model: run fewer --revolutions or a smaller load";
  throw std::runtime_error(
      fmt::format("transient ({}, {:g} revolutions): {}; {}", what, revolutions, failure->what, advice));
}

// The command's options as given.
struct TransientArgs {
  SceneOptions scene;
  double revolutions = 10, tolerance = 1e-8, max_deflection = 0.1;
  std::string step = "adaptive", out = ".", chart = "png", name = "transient", method = "fast";
  int steps_per_period = 0, samples = 200, threads = 0;
  bool follower = false, with_error = true;
};

void add_transient_options(CLI::App& command, TransientArgs& a) {
  add_scene_options(command, a.scene);
  command.add_flag("--error-estimate,!--no-error-estimate", a.with_error,
                   "estimate each reported quantity's error against the continuum model (the default: runs the same "
                   "transient on a richer Ritz model beside it; JSON error_estimate, error_budget); "
                   "--no-error-estimate leaves it out");
  add_threads_option(command, a.threads);
  command.add_option("--method", a.method,
                     "fast (default: exact free flight, Magnus through each contact, checked against RKF45; load.mode "
                     "= \"force\" without --follower, else rkf45) or rkf45 (the paper's integrator)")
      ->check(CLI::IsMember({"fast", "rkf45"}));
  add_number_option(command, "--max-deflection", a.max_deflection, AllowedRange::above(0, 1),
                    "the small-deflection range: the run stops where the lateral tip deflection exceeds this "
                    "fraction of the length (default 0.1)");
  add_number_option(command, "--revolutions", a.revolutions, AllowedRange::above(0, 1e5),
                    "length of the run in revolutions (default 10)");
  add_number_option(command, "--tolerance", a.tolerance, AllowedRange::below(1e-12, 1),
                    "the whole error of each reported quantity, relative: the terms are raised until it is met "
                    "(with the error estimate), and the time stepping gets a tenth of it (default: the scene's "
                    "terms; RKF45's steps to 1e-8, the contact propagators to 1e-7)");
  command.add_option("--step", a.step, "adaptive (default) or fixed (the paper's Δt = (1/8)(2π/ω_max), eq. 54)")
      ->check(CLI::IsMember({"adaptive", "fixed"}));
  add_integer_option(command, "--steps-per-period", a.steps_per_period, 8, 100000,
                     "fixed steps per period of the stiffest mode: 8 is the paper's (54); default: the fewest ≥ 8 "
                     "that keep RKF45's parasitic growth of that mode under 1 % over the run");
  add_integer_option(command, "--samples-per-rev", a.samples, 8, 100000, "output samples per revolution (default 200)");
  add_chart_options(command, a.out, a.chart, "directory for NAME.csv, NAME.json and the chart");
  command.add_option("--name", a.name, "stem of the output files (default transient)");
  command.add_flag("--follower", a.follower, "the tip load follows the tip slope (F cos ψ axially, −F sin ψ laterally)");
}

// The progress lines of a run: "<what>: contact pieces k/n", then "<what>: revolutions k/n".
void report_progress(TransientOptions& o, const std::string& what, bool for_people) {
  o.progress = progress_reporter(what + ": revolutions", for_people);
  o.contact_progress = progress_reporter(what + ": contact pieces", for_people);
}

// The run's options from the command's: `tolerance` (--tolerance, where given) holds the whole
// error, so the time stepping (RKF45's steps, the contact propagators) gets a tenth of it.
TransientOptions transient_options(const TransientArgs& a, std::optional<double> tolerance) {
  TransientOptions o;
  o.revolutions = a.revolutions;
  o.adaptive = a.step == "adaptive";
  o.steps_per_period = a.steps_per_period;
  if (tolerance) o.tolerance = o.contact_tolerance = *tolerance / 10;
  o.samples_per_revolution = a.samples;
  o.follower = a.follower;
  o.method = a.method == "fast" && a.step == "adaptive" ? TransientMethod::fast : TransientMethod::rkf45;
  o.max_lateral_over_length = a.max_deflection;
  o.threads = a.threads;
  // Each contact piece may take a quarter of the work --max-seconds allows.
  o.piece_work_flops = work_limits().seconds * dense_flops_per_second / 4;
  report_progress(o, "transient", a.scene.output_format() == OutputFormat::table);
  return o;
}

// A round on `scene`: the run's model (refused past the work limits) and options, and, `with_error`,
// the richer model of its estimate; each with the rounds before (`spent`: their work estimates, to
// which this round's are added).
TransientRoundModels round_models(const Scene& scene, const TransientOptions& o, bool with_error, double& spent) {
  TransientRoundModels m{assemble_model(scene), {}, {}, o};
  double work = check_transient_work(m.model, scene, o, 1, spent), richer_work = 0;
  if (with_error) m.richer = checked_richer_models(scene, o, spent, m.richer_unavailable, richer_work);
  spent += work + richer_work;
  return m;
}

// The run, its estimate (`with_error`) and, with a `tolerance`, the terms raised to meet it
// (transient_fidelity.hpp); a raised round's progress names its terms. The richer run reports to an
// embedding (which may stop it), not to the terminal's one line.
TransientAtTolerance run_command(const Scene& scene, const TransientOptions& o, std::optional<double> tolerance,
                                 bool with_error, bool for_people) {
  double spent = 0;
  const auto build = [&](const Scene& at) {
    TransientOptions round = o;
    if (at.model.terms != scene.model.terms) {
      report_progress(round, fmt::format("transient: {} terms", at.model.terms), for_people);
    }
    return round_models(at, round, with_error, spent);
  };
  const auto richer_progress = progress_reporter("transient: richer model", false);
  if (tolerance) return run_transient_to_tolerance(scene, *tolerance, build, richer_progress);
  TransientRoundModels models = build(scene);
  EstimatedTransient run = run_transient_round(models, scene, richer_progress);
  return {std::move(run), std::move(models.model), true, {}};
}

}  // namespace

Command register_transient(CLI::App& app) {
  auto* command = app.add_subcommand("transient", "time response of the blade to the tip rub (RKF45)");
  auto args = std::make_shared<TransientArgs>();
  add_transient_options(*command, *args);
  return [=] {
    if (args->step == "fixed" && args->method == "fast" && command->count("--method") > 0) {
      throw InputError("--step fixed: the fixed step (54) is RKF45's; give --method rkf45 or leave out --method");
    }
    if (command->count("--steps-per-period") > 0 && args->step != "fixed") {
      throw InputError(fmt::format("--steps-per-period {}: must be in [8, 100000] (8 is the paper's (54)), with --step "
                                   "fixed", args->steps_per_period));
    }
    check_file_stem(args->name);
    check_output_directory("--out", args->out);
    const Scene scene = args->scene.load();
    if (scene.operation.speed_rad_s <= 0) {
      throw InputError("operation.speed_rad_s = 0: the transient is counted in revolutions; give a speed > 0");
    }
    const std::optional<double> tolerance =
        command->count("--tolerance") > 0 ? std::optional(args->tolerance) : std::nullopt;
    const TransientOptions o = transient_options(*args, tolerance);
    TransientAtTolerance run = run_command(scene, o, args->with_error ? tolerance : std::nullopt, args->with_error,
                                                 args->scene.output_format() == OutputFormat::table);
    const TransientResult& r = run.run.result;
    const TransientSummary s = summarize(r, args->samples * scene.operation.speed_rad_s / two_pi);
    refuse_failed_run(s, r, o, args->tolerance, args->revolutions, scene.blade.length);

    const PrintedDigits digits = args->scene.printed_digits();
    const PrintedRun shown(digits, o.adaptive ? std::optional(o.tolerance) : std::nullopt);
    TransientResult printed = as_printed(r, shown);
    TransientSummary printed_summary = as_printed(s, shown);
    with_whole_error(printed, printed_summary, r, s, run.run.error, digits);
    // A work limit's stop names the option that sets it.
    const auto limit_named = [](const std::string& why, bool work_limited) {
      return work_limited ? with_max_seconds(why) : why;
    };
    run.tolerance_unmet = limit_named(run.tolerance_unmet, run.work_limited);
    run.run.error_unavailable = limit_named(run.run.error_unavailable, run.run.work_limited);
    const PrintedError shown_error{run.run.error, run.run.error_unavailable, digits,
                                   args->with_error ? tolerance : std::nullopt, run.tolerance_unmet};
    const std::vector<std::string> files =
        write_outputs(args->out, args->name, {{args->name + ".csv", history_csv(printed)}},
                      summary_json(scene, run.model, printed, printed_summary, o.adaptive, true, shown_error), "transient",
                      args->chart);
    if (!run.tolerance_met) print_note("transient: --" + run.tolerance_unmet + "; the answer stands with its estimate");
    switch (args->scene.output_format()) {
      case OutputFormat::json:
        print_json_answer(summary_json(scene, run.model, printed, printed_summary, o.adaptive, false, shown_error));
        break;
      case OutputFormat::csv: fmt::print("{}", history_csv(printed)); break;
      case OutputFormat::table:
        print_table(scene, run.model, o, printed, printed_summary,
                    s.checks.energy_error_j / std::max(s.checks.vibration_energy_j, 1e-300), shown_error);
        print_error(shown_error, run.model, s.sampling);
        fmt::print("written    {}\n", fmt::join(files, ", "));
    }
  };
}

}  // namespace bladestab::cli
