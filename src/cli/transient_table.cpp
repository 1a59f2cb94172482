// The transient command's table (transient_output.hpp).

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "options.hpp"
#include "transient_output.hpp"

namespace bladestab::cli {
namespace {

// A quantity the run counts (the casing's contacts): printed as counted, with its error beside it.
bool is_count(const std::string& name) { return name == "contact_closures"; }

// The method line(s) of the table: the fast method's pieces and its check, or why RKF45 ran.
void print_method(const TransientOptions& o, const TransientResult& r) {
  if (r.method == TransientMethod::fast && r.contact) {
    fmt::print("method     fast: free flight exact (one exponential per distinct interval, {} in all), casing contacts "
               "by RKF78 at rtol {:g} ({} steps, {} rejected, {} RHS evaluations, {} events located)\n",
               r.exact.free_exponentials, o.contact_tolerance, r.steps.accepted, r.steps.rejected, r.steps.evaluations,
               r.steps.event_landings);
  } else if (r.method == TransientMethod::fast) {
    fmt::print("method     fast: free flight exact (one exponential per distinct interval, {} in all), {} contact "
               "piece(s) by Magnus ({} steps in all, propagators within {:.2g} of tolerance {:g})\n",
               r.exact.free_exponentials, r.exact.contact_pieces, r.exact.magnus_steps, r.exact.contact_error,
               o.contact_tolerance);
  } else if (!r.fallback.empty()) {
    fmt::print("method     rkf45, not fast: {}\n", r.fallback);
  }
  if (const std::optional<SelfCheck>& c = r.self_check) {
    fmt::print("check      against {} (rtol {:g}) to revolution {:.4g}: states differ by {:.2g} of {} "
               "(allowed {:.2g})\n",
               c->reference == "rkf78" ? "RKF78 (Boost.Odeint)" : "RKF45", c->reference_tolerance,
               c->until_revolutions, c->difference,
               c->relative_to_resolution ? "the reference's resolution (no vibration above it)" : "the vibration",
               c->allowed);
  }
  if (r.stopped) fmt::print("stopped    at revolution {:.4g}: {}\n", r.stopped->revolution, r.stopped->reason);
}

// A length in mm as printed, with its whole error (as the JSON prints it) where the estimate has one.
std::string millimetres(double printed_m, const TransientQuantity* q, const PrintedDigits& digits) {
  return q ? fmt::format("{:.6g} ± {:.6g} mm", 1e3 * printed_m, 1e3 * digits.measure(q->budget.total()))
           : fmt::format("{:.6g} mm", 1e3 * printed_m);
}

// The `error` line: each quantity's whole error and its parts, or why there are none.
void print_error_line(const PrintedError& error) {
  if (!error.estimate) {
    fmt::print("error      {}\n", error.unavailable.empty() ? "not estimated (--no-error-estimate): the digits are the "
                                                               "time stepping's, not the continuum model's"
                                                             : "not estimated: " + error.unavailable);
    return;
  }
  std::vector<std::string> parts, unbounded;
  for (const TransientQuantity& q : error.estimate->quantities) {
    if (!q.budget.unbounded.empty()) {
      parts.push_back(fmt::format("{} not bounded", q.name));
      for (const std::string& why : q.budget.unbounded) {
        if (std::find(unbounded.begin(), unbounded.end(), why) == unbounded.end()) unbounded.push_back(why);
      }
      continue;
    }
    const double total = q.budget.total();
    parts.push_back(fmt::format("{} {} ± {} (basis {}, method {})", q.name,
                                is_count(q.name) ? q.value : error.digits.absolute(q.value, total),
                                error.digits.measure(total), error.digits.measure(q.budget.basis),
                                error.digits.measure(q.budget.method)));
  }
  fmt::print("error      against the continuum model (basis: against {} terms): {}{}\n",
             fmt::join(error.estimate->reference_terms, " and "),
             fmt::join(parts, "; "), unbounded.empty() ? "" : fmt::format(" ({})", fmt::join(unbounded, "; ")));
}

// The `tolerance` line where one was asked: the terms that meet it, or why it is not met.
void print_tolerance(const PrintedError& error, const BladeModel& model, const std::optional<PeakSampling>& sampling) {
  if (!error.tolerance) return;
  if (error.tolerance_unmet.empty()) {
    const bool coarse = sampling && !(sampling->peak_bound <= *error.tolerance);
    fmt::print("tolerance  {:g} met with {} terms per field{}\n", *error.tolerance, model.spec.terms,
               coarse ? " by the samples' peaks (see sampling: between them a peak may pass it)" : "");
  } else {
    fmt::print("tolerance  --{}; the answer stands with its estimate\n", error.tolerance_unmet);
  }
}

}  // namespace

void print_error(const PrintedError& error, const BladeModel& model, const std::optional<PeakSampling>& sampling) {
  print_error_line(error);
  print_tolerance(error, model, sampling);
}

void print_table(const Scene& scene, const BladeModel& model, const TransientOptions& o, const TransientResult& r,
                 const TransientSummary& s, double energy_fraction, const PrintedError& shown) {
    const std::optional<TransientErrorEstimate>& error = shown.estimate;
    fmt::print("scene      {}\nmodel      {}\n", scene.source, describe_model(model));
    fmt::print("load       {}\n", load_description(scene));
    print_method(o, r);
    if (r.method == TransientMethod::rkf45) fmt::print("steps      {}: {} accepted, {} rejected, {} RHS evaluations, step {:.3g} … {:.3g} s\n",
               o.adaptive ? fmt::format("adaptive RKF45, rtol {:g}, steps ≤ {:.4g} s (1/{} of the stiffest period: "
                                        "its parasitic growth ≤ ×{:.4g})",
                                        o.tolerance, r.fixed.step_s, r.fixed.steps_per_period, r.fixed.parasitic_growth)
                          : fmt::format("fixed RKF45, Δt = {:.6g} s = 1/{} of the stiffest period (54), "
                                        "its parasitic growth ×{:.4g}",
                                        r.fixed.step_s, r.fixed.steps_per_period, r.fixed.parasitic_growth),
               r.steps.accepted, r.steps.rejected, r.steps.evaluations, r.steps.smallest_step, r.steps.largest_step);
    const auto hz = [](const std::optional<double>& f) { return f ? fmt::format("{:.5g} Hz", *f) : std::string("n/a"); };
    fmt::print("tip        lateral peak {}, dominant {}; axial mean {} (static {:.6g} mm), peak {}, dominant {}\n",
               millimetres(s.peak_lateral_m, estimated(error, "peak_tip_lateral_m"), shown.digits), hz(s.lateral_hz),
               millimetres(s.mean_axial_m, estimated(error, "mean_tip_axial_m"), shown.digits),
               1e3 * r.static_tip_axial_m,
               millimetres(s.peak_axial_m, estimated(error, "peak_tip_axial_m"), shown.digits), hz(s.axial_hz));
    if (const std::optional<PeakSampling>& p = s.sampling; p && p->samples_per_period < 20) {
      fmt::print("sampling   the peaks are the samples' largest, their ± too: the {:.5g} Hz response has {:.3g} samples "
                 "a period, between which it can peak up to {} higher; --samples-per-rev resolves it\n",
                 p->frequency_hz, p->samples_per_period,
                 std::isfinite(p->peak_bound) ? fmt::format("{:.2g} %", 100 * p->peak_bound) : std::string("unboundedly"));
    }
    if (r.contact) {
      // Each with its whole error where the run has one (unit: the factor to the printed unit); the
      // count as the run counted it (outputs.md: integers are unchanged), 13 ± 17.
      const auto with_error = [&](double printed, const char* name, double unit) {
        const TransientQuantity* q = estimated(error, name);
        const double value = is_count(name) ? printed : shown.digits.absolute(printed, q ? q->budget.total() : 0);
        return q ? fmt::format("{:.6g} ± {:.2g}", unit * value, unit * shown.digits.measure(q->budget.total()))
                 : fmt::format("{:.6g}", unit * printed);
      };
      // F̄ of the peak force to two digits at most: the force is known to its estimate only.
      fmt::print("casing     {} contacts, {} ms in all; peak force {} kN (F̄ = {:.2g}) at the deepest overlap "
                 "{} µm of the penalty wall (k = {:.4g} N/m)\n",
                 with_error(r.contact->closures, "contact_closures", 1), with_error(r.contact->contact_time_s, "contact_time_s", 1e3),
                 with_error(r.contact->peak_force_n, "contact_peak_force_n", 1e-3),
                 r.contact->peak_force_n / BladeProperties(scene.blade).critical_load(),
                 with_error(r.contact->max_overlap_m, "contact_max_overlap_m", 1e6), r.contact->stiffness_n_m);
    }
    const bool rounding = s.checks.energy_rounding_j > TransientChecks::max_energy_error * s.checks.vibration_energy_j;
    if (const std::string unchecked = energy_balance_unchecked(r); !unchecked.empty()) {
      fmt::print("energy     balance not checked: {}\n", unchecked);
    } else {
      fmt::print("energy     balance E(t) − E(0) − W(t) within {:.3g} J{}{}\n", s.checks.energy_error_j,
                 s.checks.vibration_energy_j > 0 ? fmt::format(", {:.3g} of the vibration energy {:.4g} J",
                                                               energy_fraction, s.checks.vibration_energy_j)
                                                 : std::string(" (no vibration)"),
                 rounding ? fmt::format(" (E's own rounding: {:.2g} J)", s.checks.energy_rounding_j) : std::string());
    }
    if (r.growth.omitted.empty()) {
      fmt::print("growth     {:.7g} ± {:.2g} per revolution ({})\n", r.growth.growth,
                 PrintedDigits().measure(r.growth.error_estimate),
                 !r.continued_log_change.empty()
                     ? fmt::format("the state's change over the last whole revolution{}, carried on by that "
                                   "revolution's propagators for {} revolutions",
                                   r.stopped ? " before the stop" : "", r.continued_log_change.size())
                 : r.stopped ? "the last two ratios of the state's change over a revolution before the stop"
                             : "the state's change over each revolution, second half of the run");
    } else {
      fmt::print("growth     not reported: {}\n", r.growth.omitted);
    }
}

const TransientQuantity* estimated(const std::optional<TransientErrorEstimate>& e, const std::string& name) {
  if (!e) return nullptr;
  for (const TransientQuantity& q : e->quantities) {
    if (q.name == name && q.budget.unbounded.empty()) return &q;
  }
  return nullptr;
}

std::string load_description(const Scene& scene) {
  const LoadSpec& l = scene.load;
  const std::string pulses = l.pulse_count == 1 ? "" : fmt::format(" ({} in all)", l.pulse_count == 0 ? std::string("endless") : std::to_string(l.pulse_count));
  if (l.mode == LoadMode::clearance) {
    return fmt::format("casing at clearance {:g} mm with {} distortions {:g} mm deep{}, t̄c = {:g}, μ = {:g}", 1e3 * l.clearance,
                       to_string(l.profile), 1e3 * l.intrusion, pulses, l.contact_time_rev, l.friction);
  }
  return fmt::format("{} pulses{}, F̄ = {:g}, t̄c = {:g}, μ = {:g}", to_string(l.profile), pulses, l.fmax_over_fcr,
                     l.contact_time_rev, l.friction);
}

std::optional<PeakSampling> peak_sampling(const TransientSummary& s) {
  const double fastest = std::max(s.lateral_hz.value_or(0), s.axial_hz.value_or(0));
  if (!(fastest > 0) || !(s.sample_rate_hz > 0)) return std::nullopt;
  const double n = s.sample_rate_hz / fastest;
  return PeakSampling{fastest, n, n > 2 ? 1 / std::cos(pi / n) - 1 : HUGE_VAL};
}

}  // namespace bladestab::cli
