// bladestab check SCENE: does the blade meet the [requirements] of its scene over its operating
// range (requirements_check.hpp)? A table, JSON or JUnit XML for CI servers; exit 0 when every
// requirement holds, 1 when one fails or gets no verdict (its computation failed), 2 on bad input.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/stability/boundaries.hpp"
#include "bladestab/stability/requirements_check.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "commands.hpp"
#include "embedding.hpp"
#include "json_output.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "printed_digits.hpp"
#include "progress.hpp"
#include "static_limits_output.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

// One requirement's verdict as every format shows it.
struct CheckOutcome {
  std::string name;
  bool passed = false;
  bool error = false;   // no verdict: the check's own computation failed (NumericalError); `detail` says how
  std::string summary;  // the worst point in one line, for the table
  std::string detail;   // what was found and how, in sentences
  double seconds = 0;
  std::function<void(Json&, const PrintedDigits&)> write_worst;  // the "worst" object and the check's extras
};

std::string orders_text(const std::vector<int>& orders) { return fmt::format("{}", fmt::join(orders, ", ")); }

CheckOutcome margin_outcome(const Scene& scene, const FrequencyMarginResult& m) {
  const RequirementsSpec& req = *scene.requirements;
  const EngineOrderApproach& w = m.worst;
  CheckOutcome o;
  o.name = "campbell_margin";
  o.passed = m.passed;
  o.summary = fmt::format("margin {:.4g} (required {:g}): mode {}, engine order {} at {:.6g} rad/s, {:.6g} Hz",
                          w.distance, m.required, w.mode, w.engine_order, w.speed_rad_s, w.frequency_hz);
  const std::string scope = fmt::format(
      "{} mode{} below {:.6g} Hz against engine orders {} over {:g} to {:g} rad/s ({} speeds, {} terms/field, "
      "frequencies to {:g})",
      m.modes_checked, m.modes_checked == 1 ? "" : "s", m.threshold_hz, orders_text(req.engine_orders),
      m.speed_lo_rad_s, m.speed_hi_rad_s, m.speeds, m.terms, m.tolerance);
  if (w.distance == 0) {
    o.detail = fmt::format("mode {} crosses engine order {} at {:.9g} rad/s ({:.9g} Hz) inside the range: margin 0 < "
                           "{:g}; checked {}",
                           w.mode, w.engine_order, w.speed_rad_s, w.frequency_hz, m.required, scope);
  } else {
    o.detail = fmt::format("closest: mode {} to engine order {} at {:.9g} rad/s ({:.9g} Hz), |f - kΩ/2π|/f = {:.6g} "
                           "(error estimate {}), {} the required {:g}; checked {}",
                           w.mode, w.engine_order, w.speed_rad_s, w.frequency_hz, w.distance, estimate_text(m.error_estimate),
                           m.passed ? "at least" : "below", m.required, scope);
  }
  // The frequency to its tolerance, the margin to its estimate; the speed found by the search has
  // no estimate of its own (6 digits, printed_digits.hpp).
  o.write_worst = [m](Json& json, const PrintedDigits& digits) {
    json["worst"] = {{"mode", m.worst.mode},
                     {"engine_order", m.worst.engine_order},
                     {"speed_rad_s", digits.unestimated(m.worst.speed_rad_s)},
                     {"frequency_hz", digits.relative(m.worst.frequency_hz, m.tolerance)},
                     {"margin", digits.absolute(m.worst.distance, digits.estimate(m.error_estimate))}};
    json["required"] = m.required;
    json["error_estimate"] = digits.estimate(m.error_estimate);
    json["modes_checked"] = m.modes_checked;
    json["threshold_hz"] = m.threshold_hz;
    json["terms"] = m.terms;
  };
  return o;
}

const char* sign_text(int multiplier) { return multiplier < 0 ? "-1" : "+1"; }

// The onset to its estimate; the speeds found by the scan and the search, the Floquet check's
// point and its max|ρ| have no estimate of their own (6 digits, printed_digits.hpp).
void write_rub_worst(const RubStabilityResult& r, Json& json, const PrintedDigits& digits) {
  const std::optional<double> onset = r.onset_fmax_over_fcr;
  const Json shown_onset = onset ? Json(digits.relative(*onset, r.onset_error_estimate)) : Json(nullptr);
  // null where there is no region (its label) or no Floquet check (a required load of 0).
  const auto of_region = [&onset](int label) { return onset ? Json(label) : Json(nullptr); };
  const bool checked = r.required > 0;
  const auto of_check = [&](double value) { return checked ? Json(digits.unestimated(value)) : Json(nullptr); };
  json["worst"] = {{"speed_rad_s", digits.unestimated(r.speed_rad_s)},
                   {"onset_fmax_over_fcr", shown_onset},
                   {"mode", of_region(r.mode)},
                   {"order", of_region(r.order)},
                   {"multiplier", of_region(r.multiplier)},
                   {"tip", r.tip},
                   {"check_speed_rad_s", of_check(r.check_speed_rad_s)},
                   {"check_fmax_over_fcr", of_check(r.check_fmax_over_fcr)},
                   {"max_abs_multiplier", of_check(r.max_abs_multiplier)},
                   {"check_tolerance_met", r.check_tolerance_unmet.empty()}};
  json["required"] = r.required;
  json["error_estimate"] = digits.estimate(r.onset_error_estimate);
  json["onset_converged"] = r.onset_converged;
  json["unconverged_boundaries"] = r.unconverged_boundaries;
  json["window_fmax_over_fcr"] = r.window_fmax_over_fcr;
  json["approximation"] = r.approximation;
  json["speeds_scanned"] = r.speeds_scanned;
}

CheckOutcome rub_outcome(const Scene& scene, const RubStabilityResult& r) {
  CheckOutcome o;
  o.name = "rub_stability";
  o.passed = r.passed;
  // "F̄ = 0.62", or "F̄ > 2" where no region opens within the window.
  const std::string onset = r.onset_fmax_over_fcr ? fmt::format("F̄ = {:.6g}", *r.onset_fmax_over_fcr)
                                                  : fmt::format("F̄ > {:g}", r.window_fmax_over_fcr);
  // No Floquet point where only the unloaded blade is required (JSON's nulls).
  o.summary = fmt::format("lowest onset {} (required stable to {:g}) at {:.6g} rad/s; {}", onset, r.required,
                          r.speed_rad_s,
                          r.required > 0 ? fmt::format("max|ρ| = {:.6g} at F̄ = {:.4g}", r.max_abs_multiplier,
                                                       r.check_fmax_over_fcr)
                                         : std::string("no Floquet check (only the unloaded blade)"));
  const std::string scope = fmt::format(
      "θ = {}·Ω over {:g} to {:g} rad/s, load {} ({}), damping {}; regions of order <= {} sought up to F̄ = {:g} "
      "from the boundary equations at {} speeds{}",
      r.pulses_per_rev, r.speed_lo_rad_s, r.speed_hi_rad_s, to_string(scene.load.profile),
      to_string(scene.load.approximation), to_string(scene.damping.model), r.max_order, r.window_fmax_over_fcr,
      r.speeds_scanned,
      r.floquet_speeds > 0 ? fmt::format("; Floquet at the requirement at {} speeds across it", r.floquet_speeds) : "");
  const std::string floquet =
      fmt::format("Floquet at {:.9g} rad/s, F̄ = {:.6g}: max|ρ| = {:.8g} ({}{})", r.check_speed_rad_s,
                  r.check_fmax_over_fcr, r.max_abs_multiplier, r.check_stable ? "stable" : "unstable",
                  r.check_tolerance_unmet.empty() ? "" : "; its " + r.check_tolerance_unmet);
  const std::string estimate = r.onset_converged ? "error estimate " + estimate_text(r.onset_error_estimate)
                                                 : "not converged in the harmonics";
  const std::string unconverged =
      r.unconverged_boundaries == 0
          ? ""
          : fmt::format("; {} boundaries at the worst speed did not converge in the harmonics (regions end at their "
                        "last values)", r.unconverged_boundaries);
  if (r.required == 0) {
    o.detail = "max_fmax_over_fcr = 0: only the unloaded blade, which no rub excites";
  } else if (r.tip) {
    o.detail = fmt::format(
        "undamped: the region of mode {}, order {} (multiplier {}) touches F̄ = 0 at its tip 2ω_{}/{} = {}·Ω, "
        "Ω = {:.9g} rad/s, inside the range, so a rub of any load opens it (onset 0); {}{}; {}",
        r.mode, r.order, sign_text(r.multiplier), r.mode, r.order, r.pulses_per_rev, r.speed_rad_s, floquet,
        r.check_stable ? " (the region bends away from its tip's speed as F̄ grows, the compression lowering the "
                         "frequencies, so this point is outside it: no confirmation)"
                       : "",
        scope);
  } else if (r.onset_fmax_over_fcr && *r.onset_fmax_over_fcr <= r.required) {
    o.detail = fmt::format("a region of mode {}, order {} (multiplier {}) opens at F̄ = {:.8g} ({}) "
                           "at {:.9g} rad/s, within the required {:g}; {}; {}{}",
                           r.mode, r.order, sign_text(r.multiplier), *r.onset_fmax_over_fcr, estimate,
                           r.speed_rad_s, r.required, floquet, scope, unconverged);
  } else if (!r.check_stable) {
    // The regions sought end at order max_order: at low speeds θ = kΩ meets tongues of far higher
    // order (at 10 rad/s mode 1's principal one is of order ~46).
    o.detail = fmt::format("no ±1 region of order <= {} opens below the required F̄ = {:g} (the lowest: {}), but {}: "
                           "a combination resonance (multipliers leaving the unit circle away from ±1) or a region of "
                           "higher order; {}{}",
                           r.max_order, r.required, onset, floquet, scope, unconverged);
  } else {
    o.detail = fmt::format("the lowest onset, {}{} at {:.9g} rad/s{}, is above the required {:g}; {}; {}{}", onset,
                           r.onset_fmax_over_fcr ? fmt::format(" ({})", estimate) : "",
                           r.speed_rad_s,
                           r.onset_fmax_over_fcr ? fmt::format(" (mode {}, order {}, multiplier {})", r.mode, r.order,
                                                               sign_text(r.multiplier))
                                                 : "",
                           r.required, floquet, scope, unconverged);
  }
  o.write_worst = [r](Json& json, const PrintedDigits& digits) { write_rub_worst(r, json, digits); };
  return o;
}

CheckOutcome static_limits_outcome(const StaticLimitsResult& l) {
  CheckOutcome o;
  o.name = "static_limits";
  o.passed = l.passed;
  o.summary = describe_path_limits(l.path, true, speed_parameter().words);
  o.detail = fmt::format("{}, inside the speed range: the other requirements are checked from {:g} to {:g} rad/s, "
                         "the part within the blade's static limits",
                         o.summary, l.speed_lo_rad_s, l.speed_hi_rad_s);
  o.write_worst = [l](Json& json, const PrintedDigits& digits) {
    write_static_limits(json, l.path, speed_parameter(), "check", digits);
    json["speed_lo_rad_s"] = l.speed_lo_rad_s;
    json["speed_hi_rad_s"] = l.speed_hi_rad_s;
  };
  return o;
}

// A requirement whose computation fails in one line (a work limit, a check of its own): no verdict,
// and not passed, while the other requirements keep theirs (JUnit: an <error>, not a <failure>).
template <class Check>
CheckOutcome outcome_or_error(const std::string& name, Check check) {
  const auto start = std::chrono::steady_clock::now();
  CheckOutcome o;
  try {
    o = check();
  } catch (const NumericalError& e) {
    o.name = name;
    o.error = true;
    o.summary = "no verdict: the check failed";
    o.detail = fmt::format("no verdict: {}", e.what());
    o.write_worst = [message = std::string(e.what())](Json& json, const PrintedDigits&) {
      json["worst"] = nullptr;
      json["error"] = message;
    };
  }
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return o;
}

bool all_passed(const std::vector<CheckOutcome>& checks) {
  return std::all_of(checks.begin(), checks.end(), [](const CheckOutcome& c) { return c.passed; });
}

std::string check_json(const Scene& scene, double tolerance, const std::vector<CheckOutcome>& checks,
                       const PrintedDigits& digits) {
  Json json = {{"passed", all_passed(checks)}, {"scene", scene.source}, {"tolerance", tolerance}, {"checks", Json::array()}};
  for (const CheckOutcome& c : checks) {
    Json& check = json["checks"].emplace_back(Json{{"name", c.name}, {"passed", c.passed}});
    c.write_worst(check, digits);
    check["detail"] = c.detail;
    check["seconds"] = digits.unestimated(c.seconds);
  }
  return json_text(json);
}

// Text for XML attributes and content: the five special characters escaped, and the control
// characters XML 1.0 does not allow dropped.
std::string xml_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\n' || c == '\t') out += c;
    }
  }
  return out;
}

// One <testsuite> with a <testcase> per requirement, as JUnit's XML (read by GitLab, Jenkins and
// the GitHub Actions reporters); a failed requirement carries a <failure>.
std::string check_junit(const Scene& scene, const std::vector<CheckOutcome>& checks) {
  double seconds = 0;
  int failures = 0, errors = 0;
  for (const CheckOutcome& c : checks) seconds += c.seconds, failures += !c.passed && !c.error, errors += c.error;
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += fmt::format("<testsuite name=\"bladestab check\" tests=\"{}\" failures=\"{}\" errors=\"{}\" time=\"{:.3f}\">\n",
                     checks.size(), failures, errors, seconds);
  for (const CheckOutcome& c : checks) {
    xml += fmt::format("  <testcase classname=\"{}\" name=\"{}\" time=\"{:.3f}\">\n", xml_escaped(scene_title(scene)),
                       c.name, c.seconds);
    if (!c.passed) {
      xml += fmt::format("    <{0} message=\"{1}\">{2}</{0}>\n", c.error ? "error" : "failure", xml_escaped(c.summary),
                         xml_escaped(c.detail));
    }
    xml += fmt::format("    <system-out>{}</system-out>\n  </testcase>\n", xml_escaped(c.detail));
  }
  return xml + "</testsuite>\n";
}

void print_table(const Scene& scene, const std::vector<CheckOutcome>& checks) {
  const RequirementsSpec& req = *scene.requirements;
  fmt::print("scene   {}\nrange   {:g} to {:g} rad/s\n\n", scene.source, req.speed_lo_rad_s, req.speed_hi_rad_s);
  fmt::print("{:<16} {:<6} {}\n", "requirement", "result", "worst");
  for (const CheckOutcome& c : checks) {
    fmt::print("{:<16} {:<6} {}\n", c.name, c.passed ? "pass" : c.error ? "ERROR" : "FAIL", c.summary);
  }
  fmt::print("\n");
  for (const CheckOutcome& c : checks) fmt::print("{}: {}\n", c.name, c.detail);
  const long errors = std::count_if(checks.begin(), checks.end(), [](const CheckOutcome& c) { return c.error; });
  const long failed =
      std::count_if(checks.begin(), checks.end(), [](const CheckOutcome& c) { return !c.passed; }) - errors;
  std::vector<std::string> verdicts;
  if (failed > 0) verdicts.push_back(fmt::format("{} of {} requirements not met", failed, checks.size()));
  if (errors > 0) verdicts.push_back(fmt::format("{} of {} without a verdict", errors, checks.size()));
  fmt::print("\n{}\n", verdicts.empty() ? "all requirements hold" : fmt::format("{}", fmt::join(verdicts, "; ")));
}

// The dense eigensolves the checks cannot do without, before they start: the Campbell diagram's
// whole-model solves of the scene's model and its richer reference at three sample speeds
// (whole_eigensolve_flops each), and the converged boundary equations at the worst speed, both families
// at k = 2 and 4 on the whole model and at k = 2 on the richer one (boundary_level_flops and
// boundary_level_bytes). A lower bound: the scan and the Floquet checks come on top.
void check_requirements_work(const Scene& scene) {
  const RequirementsSpec& req = *scene.requirements;
  ModelSpec richer = scene.model;
  richer.terms = reference_terms(scene.model.basis, scene.model.terms);
  const double n = dof_layout(scene.model, scene.blade.two_planes()).size(), nr = dof_layout(richer, scene.blade.two_planes()).size();
  double flops = 0, bytes = 0;
  if (req.frequency_margin) {
    for (const double dofs : {n, nr}) {
      flops += 3 * whole_eigensolve_flops(dofs, scene.damping.damped());
      bytes = std::max(bytes, eigensolve_bytes(dofs));
    }
  }
  if (req.max_fmax_over_fcr) {
    for (const auto& [k, dofs] : {std::pair{2, n}, {4, n}, {2, nr}}) {
      flops += boundary_level_flops(k, static_cast<int>(dofs), false);
      bytes = std::max(bytes, boundary_level_bytes(k, static_cast<int>(dofs), false));
    }
  }
  check_work(fmt::format("the requirements with model.terms = {}", scene.model.terms),
             "the whole-model eigensolves of the checks", flops / dense_flops_per_second, bytes);
}

}  // namespace

Command register_check(CLI::App& app) {
  auto* command = app.add_subcommand("check", "does the blade meet the scene's [requirements]? (for CI; exit 1 if not)");
  auto options = std::make_shared<SceneOptions>();
  auto tolerance = std::make_shared<double>(1e-6);
  add_scene_options(*command, *options, {"table", "json", "junit"});
  add_number_option(*command, "--tolerance", *tolerance, AllowedRange::open(0, 1),
                    "wanted relative error of the Campbell frequencies; the terms are raised until it is met "
                    "(default 1e-6)");
  return [=] {
    check_tolerance(*tolerance);
    const Scene scene = options->load();
    refuse_impulse_jump(scene);  // before the sweeps: the check ends with a Floquet answer
    if (!scene.requirements) {
      throw InputError(fmt::format("{}: [requirements]: missing section; `check` needs one with "
                                   "speed_range_rad_s and frequency_margin and/or max_fmax_over_fcr",
                                   scene.source));
    }
    check_requirements_work(scene);
    const bool for_people = options->format == "table";
    std::vector<CheckOutcome> checks;
    // Listed only where it fails: a range within the limits adds no check.
    CheckOutcome limits =
        outcome_or_error("static_limits", [&] { return static_limits_outcome(check_static_limits(scene)); });
    if (!limits.passed) checks.push_back(std::move(limits));
    if (scene.requirements->frequency_margin) {
      checks.push_back(outcome_or_error("campbell_margin", [&] {
        return margin_outcome(scene, check_frequency_margin(scene, *tolerance,
                                                            progress_reporter("check: Campbell speeds", for_people),
                                                            work_limits().seconds * dense_flops_per_second / 2));
      }));
    }
    if (scene.requirements->max_fmax_over_fcr) {
      checks.push_back(outcome_or_error("rub_stability", [&] {
        return rub_outcome(scene, check_rub_stability(scene, progress_reporter("check: rub speeds", for_people),
                                                      work_limits().seconds * dense_flops_per_second));
      }));
    }
    if (options->format == "json") {
      print_json_answer(check_json(scene, *tolerance, checks, options->printed_digits()));
    } else if (options->format == "junit") {
      fmt::print("{}", check_junit(scene, checks));
    } else {
      print_table(scene, checks);
    }
    if (!all_passed(checks)) throw AnswerIsNegative{};
  };
}

}  // namespace bladestab::cli
