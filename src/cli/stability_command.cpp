// bladestab stability SCENE: Floquet multipliers at the scene's operating point.
#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/stability/stability_analysis.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/stability/matrix_export.hpp"
#include "support/message_text.hpp"
#include "bladestab/scene/scene_limits.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "commands.hpp"
#include "embedding.hpp"
#include "error_output.hpp"
#include "finite_results.hpp"
#include "json_output.hpp"
#include "notes.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "work_limits.hpp"
#include "output_files.hpp"

namespace bladestab::cli {
namespace {

// In the order --help lists them.
constexpr std::initializer_list<FloquetMethod> methods{FloquetMethod::hill, FloquetMethod::koopman_hill,
                                                      FloquetMethod::monodromy, FloquetMethod::monodromy_rkf45,
                                                      FloquetMethod::automatic};

// Why the tolerance is not met, as the output prints it: "--tolerance …", with the option that set
// the work limit where that stopped the fidelity.
std::string unmet_text(const StabilityAnswer& a) {
  return "--" + (a.work_limited ? with_max_seconds(a.tolerance_unmet) : a.tolerance_unmet);
}

std::string truncation(const FloquetResult& r, bool exact_pulse) {
  if (r.method == FloquetMethod::monodromy_rkf45) return "RKF45 at 1/1000 of the tolerance and at 1/100 of that";
  if (exact_pulse) return fmt::format("{} Magnus steps through the contact, exact between pulses", r.steps);
  return r.method == FloquetMethod::monodromy ? fmt::format("{} Magnus steps per period", r.steps)
                                              : fmt::format("q = {} harmonics", r.harmonics);
}

// "2.1e-13", or "not informative" for NaN.
std::string check_value(double v) { return std::isnan(v) ? "n/a" : fmt::format("{:.1e}", v); }

// The error of the log decrement δ = −2π ln|ρ| / |arg ρ| (theory.md (46)) of a multiplier ρ known to
// E (absolute): ln|ρ| and arg ρ each move by up to E/|ρ|, so δ by (2π + |δ|)/|arg ρ| · E/|ρ|.
// nullopt where ρ is not resolved (|ρ| ≤ E): δ is then only bounded below (decrement_floor).
std::optional<double> decrement_error(std::complex<double> rho, double decrement, double E) {
  if (std::abs(rho) <= E) return std::nullopt;
  return (two_pi + std::abs(decrement)) / std::abs(std::arg(rho)) * E / std::abs(rho);
}

// δ ≥ −2 ln(|ρ| + E) of an unresolved multiplier (|arg ρ| ≤ π).
double decrement_floor(std::complex<double> rho, double E) { return -2 * std::log(std::abs(rho) + E); }

// The answer's numbers as JSON and CSV print them (printed_digits.hpp): every multiplier, max|ρ| and
// the monodromy's max|ρ| to the total estimate E as printed (absolute on ρ), max Re λ = ln max|ρ| / T
// to E / (max|ρ| T), the log decrement of a multiplier to decrement_error (null where that is
// unbounded); the checks to 2 digits.
class PrintedAnswer {
public:
  PrintedAnswer(const StabilityAnswer& a, const PrintedDigits& digits)
      : a_(a), digits_(digits), error_(digits.estimate(a.budget.total())) {}
  double rho(double value) const { return digits_.absolute(value, error_); }
  double real_exponent() const {
    const double period = two_pi / a_.theta_rad_s;
    return digits_.absolute(a_.floquet.max_real_exponent, error_ / (a_.floquet.max_abs_multiplier * period));
  }
  Json log_decrement(Eigen::Index k) const {
    const std::optional<double>& d = a_.floquet.log_decrements[k];
    const std::optional<double> e = d ? decrement_error(a_.floquet.multipliers(k), *d, error_) : std::nullopt;
    return e ? Json(digits_.absolute(*d, *e)) : Json(nullptr);
  }
  Json check(double value) const { return number_or_null(digits_.measure(value)); }

private:
  const StabilityAnswer& a_;
  const PrintedDigits& digits_;
  double error_;
};

Json checks_json(const FloquetChecks& c, const PrintedAnswer& shown) {
  return {{"determinant_error", shown.check(c.determinant_error)},
          {"reciprocal_error", shown.check(c.reciprocal_error)},
          {"rkf45_residual", shown.check(c.residual)},
          {"rkf45_multiplier_error", shown.check(c.multiplier_error)},
          {"monodromy_max_abs_multiplier", shown.rho(c.monodromy_max_abs_multiplier)}};
}

void require_finite(const StabilityAnswer& a) {
  const FiniteResults check("stability");
  check.require("max|ρ|", a.floquet.max_abs_multiplier)
      .require("max Re λ", a.floquet.max_real_exponent)
      .require("error estimate", a.budget.total())
      .require("pulse frequency θ", a.theta_rad_s);
  for (Eigen::Index k = 0; k < a.floquet.multipliers.size(); ++k) {
    check.require(fmt::format("multiplier {}", k + 1), std::abs(a.floquet.multipliers(k)));
  }
}

// The answer as JSON: the scene, the model and the method chosen, max|ρ| with its error budget, the
// checks and every multiplier, each to the digits its estimate supports.
void print_json(const Scene& scene, const StabilityAnswer& a, const PrintedDigits& digits, const PrintedAnswer& shown) {
  const FloquetResult& r = a.floquet;
  const LoadSeries& load = a.load;
  Json json;
  json["scene"] = scene.source;
  json["speed_rad_s"] = scene.operation.speed_rad_s;
  json["fmax_over_fcr"] = scene.load.fmax_over_fcr;
  json["tip_compression_over_fcr"] = scene.operation.tip_compression_over_fcr;
  json["theta_rad_s"] = a.theta_rad_s;
  json["load_approximation"] = to_string(scene.load.approximation);
  json["load_harmonics"] = load.harmonics();
  json["load_relative_tail"] = digits.estimate(load.relative_tail);
  json["terms"] = a.model.terms;
  json["reference_terms"] = a.reference_terms;
  json["reduction"] = to_string(a.reduction.kind);
  json["reduction_vectors"] = a.reduction.vectors;
  json["reduced_dofs"] = a.reduced_size;
  json["full_dofs"] = a.full_size;
  json["method"] = to_string(r.method);
  json["harmonics"] = r.harmonics;
  json["steps"] = r.steps;
  json["max_abs_multiplier"] = shown.rho(r.max_abs_multiplier);
  json["max_real_exponent"] = shown.real_exponent();
  json["stable"] = a.stable;
  json["tolerance_met"] = a.tolerance_met;
  json["tolerance_unmet"] = a.tolerance_met ? Json(nullptr) : Json(unmet_text(a));
  write_error_budget(json, a.budget, digits);
  json["checks"] = checks_json(r.checks, shown);
  json["multipliers"] = Json::array();
  for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) {
    const std::complex<double> rho = r.multipliers(k);
    json["multipliers"].push_back({{"re", shown.rho(rho.real())}, {"im", shown.rho(rho.imag())}});
  }
  json["log_decrements"] = Json::array();
  for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) json["log_decrements"].push_back(shown.log_decrement(k));
  print_json_answer(json_text(json));
}

// The multipliers as CSV, one row each.
void print_csv(const FloquetResult& r, const PrintedAnswer& shown) {
  fmt::print("index,re,im,abs,log_decrement\n");
  for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) {
    const Json d = shown.log_decrement(k);
    fmt::print("{},{},{},{},{}\n", k + 1, shown.rho(r.multipliers(k).real()), shown.rho(r.multipliers(k).imag()),
               shown.rho(std::abs(r.multipliers(k))), d.is_null() ? "" : fmt::format("{}", d.get<double>()));
  }
}

// The table for people: the scene, model, reduction, load, method, error and checks, then max|ρ|
// and each multiplier to the decimals the error estimate supports.
void print_table(const Scene& scene, const StabilityAnswer& a) {
  const FloquetResult& r = a.floquet;
  const double fbar = scene.load.fmax_over_fcr;
  const double error = a.budget.total();
  const LoadSeries& load = a.load;
  const std::string other_basis =
      a.model.basis == BasisKind::sine ? fmt::format(" and {} Legendre terms", a.model.terms) : "";
  fmt::print("scene      {}\nmodel      {}, {} basis, {} terms/field (budget against {}{}), axial {}, coriolis {}\n",
             scene.source, to_string(a.model.theory), to_string(a.model.basis), a.model.terms, a.reference_terms,
             other_basis, a.model.axial ? "on" : "off", a.model.coriolis ? "on" : "off");
  fmt::print("reduction  {}\n", describe_reduction(a.reduction, a.reduced_size, a.full_size));
  fmt::print("operation  Ω = {:.6g} rad/s, {}F̄_max = {:.6g}, θ = {:.6g} rad/s; load: {}\n",
             scene.operation.speed_rad_s,
             scene.operation.tip_compression_over_fcr == 0
                 ? std::string()
                 : fmt::format("static tip compression F_a = {:.6g} F_cr, ", scene.operation.tip_compression_over_fcr),
             fbar, a.theta_rad_s,
             load.cosine_approximation ? std::string("cosine approximation (42)")
            : load.exact_pulse
                ? fmt::format("the true {} pulse train, integrated through each contact", to_string(scene.load.profile))
                : fmt::format("{} harmonics of the {} pulse (relative L2 tail {:.1e})", load.harmonics(),
                              to_string(scene.load.profile), load.relative_tail));
  fmt::print("method     {}, {}\n", to_string(r.method), truncation(r, load.exact_pulse));
  fmt::print("error      {} on max|ρ|{}\n", describe_error_budget(a.budget),
             a.tolerance_met ? "" : "  — " + unmet_text(a));
  fmt::print("checks     det Φ vs Liouville {}, reciprocal pairs {}, RKF45 on the dominant vector: multiplier {}, "
             "residual {}\n\n",
             check_value(r.checks.determinant_error), check_value(r.checks.reciprocal_error),
             check_value(r.checks.multiplier_error), check_value(r.checks.residual));
  const double relative = error / std::max(1.0, r.max_abs_multiplier);
  const double exponent_error = error / (r.max_abs_multiplier * two_pi / a.theta_rad_s);
  // Below 1 the estimate is absolute: its decade, not significant digits.
  const std::string rho = r.max_abs_multiplier < 1 ? fixed_to_error(r.max_abs_multiplier, error)
                                                   : fmt::format("{:.{}g}", r.max_abs_multiplier, significant_digits(relative));
  // "stable" is max|ρ| ≤ 1 + E: where E is above the tolerance, a growth that small is not excluded.
  const std::string verdict = !a.stable         ? "UNSTABLE"
                              : a.tolerance_met ? "stable"
                                                : fmt::format("stable within its estimate (a growth up to ×{:.3g} a "
                                                              "period is not excluded)", 1 + error);
  fmt::print("max|ρ| = {}   max Re λ = {} 1/s   → {}\n\n", rho, fixed_to_error(r.max_real_exponent, exponent_error),
             verdict);
  // Decimals the error estimate supports; from 1e6 on, the significant digits it supports.
  const int decimals = std::clamp(static_cast<int>(-std::log10(std::max(error, 1e-12))), 1, 10);
  const auto shown = [&](double x) {
    if (std::abs(x) < 1e6) return fmt::format("{:.{}f}", x, decimals);
    return fmt::format("{:.{}e}", x, significant_digits(error / std::abs(x)) - 1);
  };
  fmt::print("{:>4} {:>16} {:>16} {:>16} {:>10}\n", "#", "Re ρ", "Im ρ", "|ρ|", "log decr.");
  for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) {
    const auto& d = r.log_decrements[k];
    const std::optional<double> e = d ? decrement_error(r.multipliers(k), *d, error) : std::nullopt;
    fmt::print("{:>4} {:>16} {:>16} {:>16} {:>10}\n", k + 1, shown(r.multipliers(k).real()),
               shown(r.multipliers(k).imag()), shown(std::abs(r.multipliers(k))),
               !d ? "—" : e ? fixed_to_error(*d, std::max(*e, 1e-4)) : fmt::format("> {:.3g}", decrement_floor(r.multipliers(k), error)));
  }
}

void print(const SceneOptions& options, const Scene& scene, const StabilityAnswer& a) {
  require_finite(a);
  const PrintedDigits digits = options.printed_digits();
  const PrintedAnswer shown(a, digits);
  switch (options.output_format()) {
    case OutputFormat::json: print_json(scene, a, digits, shown); break;
    case OutputFormat::csv: print_csv(a.floquet, shown); break;
    case OutputFormat::table: print_table(scene, a); break;
  }
}

// --export-matrices FILE.json: the manifest's path must end in .json and its directory be writable;
// checked before anything is computed (an input error, exit 2).
void check_export_path(const std::string& path) {
  const std::filesystem::path p(path);
  // The temporaries beside the files (output_files.hpp) add about 30 bytes to a name of at most 255.
  if (p.extension() != ".json" || p.stem().empty() || p.filename().string().size() > 200) {
    throw InputError(fmt::format("--export-matrices {}: must be a FILE.json of at most 200 bytes (the manifest; the "
                                 "matrices go beside it as FILE.A0.mtx, FILE.B.mtx and FILE.load.mtx)",
                                 echoed(path, 240)));
  }
  check_output_directory(fmt::format("--export-matrices {}: its directory", echoed(path, 240)),
                         p.has_parent_path() ? p.parent_path().string() : ".");
}

// The system the answer's Floquet analysis integrated (its basis, reduction and load series), in
// Matrix Market files, and a manifest with everything else a reader needs; all four or none.
void export_matrices(const std::string& path, const Scene& scene, const StabilityAnswer& a, double tolerance,
                     const PrintedDigits& digits) {
  const PeriodicSystem sys = periodic_system(assemble_model(scene, a.model), scene, a.load, a.reduction);
  const ExportedArrays files = matrix_market_files(std::filesystem::path(path).replace_extension().string());
  OutputFiles output;
  write_matrix_market(sys, {output.reserve(files.A0), output.reserve(files.B), output.reserve(files.load)});
  const auto name = [](const std::string& file) { return std::filesystem::path(file).filename().string(); };
  Json json;
  json["format"] = "bladestab periodic system, Matrix Market";
  json["equation"] = "dy/dt = (A0 + (F(t) - F0) B) y,  F(t) = sum over |m| <= M of F_m exp(i m theta t), "
                     "F_-m = conj(F_m), F0 = F_0";
  json["A0"] = name(files.A0);
  json["B"] = name(files.B);
  json["load"] = name(files.load);
  json["states"] = sys.state_size();
  json["theta_rad_s"] = sys.angular_frequency;
  json["period_s"] = sys.period();
  json["load_harmonics"] = static_cast<int>(sys.coefficients.size()) - 1;
  json["scene"] = scene.source;
  json["speed_rad_s"] = scene.operation.speed_rad_s;
  json["fmax_over_fcr"] = scene.load.fmax_over_fcr;
  json["load_approximation"] = to_string(scene.load.approximation);
  json["basis"] = to_string(a.model.basis);
  json["terms"] = a.model.terms;
  json["reduction"] = to_string(a.reduction.kind);
  json["reduction_vectors"] = a.reduction.vectors;
  json["reduced_dofs"] = sys.kept_modes;
  json["full_dofs"] = sys.all_modes;
  json["method"] = to_string(a.floquet.method);
  json["tolerance"] = tolerance;
  json["max_abs_multiplier"] = PrintedAnswer(a, digits).rho(a.floquet.max_abs_multiplier);
  json["stable"] = a.stable;
  write_error_budget(json, a.budget, digits);
  output.write(path, json_text(json));
  output.commit();
}

}  // namespace

Command register_stability(CLI::App& app) {
  auto* command = app.add_subcommand("stability", "Floquet multipliers at the scene's speed and load");
  auto options = std::make_shared<SceneOptions>();
  auto method = std::make_shared<std::string>("auto");
  auto harmonics = std::make_shared<int>(0);
  auto tolerance = std::make_shared<double>(1e-6);
  auto cutoff = std::make_shared<double>(0);
  auto export_path = std::make_shared<std::string>();
  auto threads = std::make_shared<int>();
  add_scene_options(*command, *options);
  add_threads_option(*command, *threads);
  command->add_option("--method", *method, "hill, koopman-hill, monodromy (Magnus), monodromy-rkf45 or auto (default)")
      ->check(CLI::IsMember(names_of(methods)));
  add_integer_option(*command, "--harmonics", *harmonics, 1, 60,
                     "Hill truncation q (default: raised until --tolerance is met)");
  add_number_option(*command, "--tolerance", *tolerance, AllowedRange::open(0, 1),
                    "wanted accuracy of max|ρ| (default 1e-6)");
  add_number_option(*command, "--cutoff-hz", *cutoff, AllowedRange::closed(0, scene_limits::cutoff_hz.hi),
                    "modal truncation: keep only the unloaded modes below this frequency (model.reduction = "
                    "\"modal\"; default 0: the automatic reduction)");
  command->add_option("--export-matrices", *export_path,
                      "write the periodic system the analysis integrated: FILE.json (manifest) and beside it "
                      "FILE.A0.mtx, FILE.B.mtx, FILE.load.mtx (Matrix Market)");
  return [=] {
    const bool exporting = command->count("--export-matrices") > 0;
    if (exporting) check_export_path(*export_path);
    Scene scene = options->load();
    if (*cutoff > 0) {
      check_modal_cutoff(scene, *cutoff, fmt::format("--cutoff-hz {:g}", *cutoff));
      scene.model.reduction = {ReductionKind::modal, 0, *cutoff};
    }
    if (exporting && scene.load.approximation == LoadApproximation::exact) {
      throw InputError(fmt::format("--export-matrices {}: load.approximation = \"exact\" is integrated through each "
                                   "pulse and has no series to export; use \"cosine\" or \"fourier\"",
                                   echoed(*export_path, 240)));
    }
    StabilityRequest request{named(*method, methods), *harmonics, *tolerance, *threads,
                             progress_reporter("stability: refinement levels",
                                               options->output_format() == OutputFormat::table)};
    request.work_flops = work_limits().seconds * dense_flops_per_second;
    const StabilityAnswer answer = analyse_stability(scene, request);
    if (exporting) export_matrices(*export_path, scene, answer, *tolerance, options->printed_digits());
    print(*options, scene, answer);
    if (!answer.tolerance_met) print_note("stability: " + unmet_text(answer) + "; the answer stands with its estimate");
  };
}

}  // namespace bladestab::cli
