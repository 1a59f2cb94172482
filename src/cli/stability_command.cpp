// bladestab stability SCENE: Floquet multipliers at the scene's operating point.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/floquet.hpp"
#include "bladestab/input_error.hpp"
#include "commands.hpp"
#include "json_writer.hpp"
#include "options.hpp"

namespace bladestab::cli {
namespace {

FloquetMethod parse_method(const std::string& name) {
  if (name == "hill") return FloquetMethod::hill;
  if (name == "koopman-hill") return FloquetMethod::koopman_hill;
  if (name == "monodromy") return FloquetMethod::monodromy;
  if (name == "monodromy-rkf45") return FloquetMethod::monodromy_rkf45;
  return FloquetMethod::automatic;
}

std::string truncation(const FloquetResult& r) {
  if (r.method == FloquetMethod::monodromy_rkf45) return "RKF45 at the tolerance and at 1/100 of it";
  return r.method == FloquetMethod::monodromy ? fmt::format("{} Magnus steps per period", r.steps)
                                              : fmt::format("q = {} harmonics", r.harmonics);
}

void print(const SceneOptions& options, const Scene& scene, const BladeModel& model, const PeriodicSystem& sys,
           const LoadSeries& load, const FloquetResult& r) {
  const double fbar = scene.load.fmax_over_fcr;
  switch (options.output_format()) {
    case OutputFormat::json: {
      JsonWriter json;
      json.begin_object()
          .value("scene", scene.source)
          .value("speed_rad_s", scene.operation.speed_rad_s)
          .value("fmax_over_fcr", fbar)
          .value("theta_rad_s", sys.angular_frequency)
          .value("load_approximation", load.cosine_approximation ? "cosine" : "fourier")
          .value("load_harmonics", load.harmonics())
          .value("load_relative_tail", load.relative_tail)
          .value("model", describe_model(model))
          .value("kept_modes", sys.kept_modes)
          .value("method", to_string(r.method))
          .value("harmonics", r.harmonics)
          .value("steps", r.steps)
          .value("max_abs_multiplier", r.max_abs_multiplier)
          .value("max_real_exponent", r.max_real_exponent)
          .value("stable", r.stable)
          .value("error_estimate", r.error_estimate)
          .begin_array("multipliers");
      for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) {
        json.begin_object().value("re", r.multipliers(k).real()).value("im", r.multipliers(k).imag()).end_object();
      }
      json.end_array().begin_array("log_decrements");
      for (const auto& d : r.log_decrements) d ? json.element(*d) : json.null_value(nullptr);
      json.end_array().end_object();
      fmt::print("{}", json.str());
      break;
    }
    case OutputFormat::csv:
      fmt::print("index,re,im,abs,log_decrement\n");
      for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) {
        const auto& d = r.log_decrements[k];
        fmt::print("{},{},{},{},{}\n", k + 1, r.multipliers(k).real(), r.multipliers(k).imag(),
                   std::abs(r.multipliers(k)), d ? fmt::format("{}", *d) : "");
      }
      break;
    case OutputFormat::table: {
      fmt::print("scene      {}\nmodel      {} ({} of {} modes kept)\n", scene.source, describe_model(model),
                 sys.kept_modes, sys.all_modes);
      fmt::print("operation  Ω = {:.6g} rad/s, F̄_max = {:.6g}, θ = {:.6g} rad/s; load: {}\n",
                 scene.operation.speed_rad_s, fbar, sys.angular_frequency,
                 load.cosine_approximation
                     ? std::string("cosine approximation (42)")
                     : fmt::format("{} harmonics of the {} pulse (relative L2 tail {:.1e})", load.harmonics(),
                                   to_string(scene.load.profile), load.relative_tail));
      fmt::print("method     {}, {}; error estimate {:.1e} on max|ρ|\n\n", to_string(r.method), truncation(r),
                 r.error_estimate);
      const int digits = significant_digits(r.error_estimate);
      fmt::print("max|ρ| = {:.{}g}   max Re λ = {:.4g} 1/s   → {}\n\n", r.max_abs_multiplier, digits,
                 r.max_real_exponent, r.stable ? "stable" : "UNSTABLE");
      // Decimals the error estimate supports.
      const int decimals = std::clamp(static_cast<int>(-std::log10(std::max(r.error_estimate, 1e-12))), 3, 10);
      fmt::print("{:>4} {:>16} {:>16} {:>16} {:>10}\n", "#", "Re ρ", "Im ρ", "|ρ|", "log decr.");
      for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) {
        const auto& d = r.log_decrements[k];
        fmt::print("{:>4} {:>16.{}f} {:>16.{}f} {:>16.{}f} {:>10}\n", k + 1, r.multipliers(k).real(), decimals,
                   r.multipliers(k).imag(), decimals, std::abs(r.multipliers(k)), decimals,
                   d ? fmt::format("{:.4f}", *d + 0.0) : "—");
      }
      break;
    }
  }
}

}  // namespace

Command register_stability(CLI::App& app) {
  auto* command = app.add_subcommand("stability", "Floquet multipliers at the scene's speed and load");
  auto options = std::make_shared<SceneOptions>();
  auto method = std::make_shared<std::string>("auto");
  auto harmonics = std::make_shared<int>(0);
  auto tolerance = std::make_shared<double>(1e-6);
  auto cutoff = std::make_shared<double>(0);
  add_scene_options(*command, *options);
  command->add_option("--method", *method, "hill, koopman-hill, monodromy (Magnus), monodromy-rkf45 or auto (default)")
      ->check(CLI::IsMember({"hill", "koopman-hill", "monodromy", "monodromy-rkf45", "auto"}));
  command->add_option("--harmonics", *harmonics, "Hill truncation q (default: raised until --tolerance is met)");
  command->add_option("--tolerance", *tolerance, "wanted accuracy of max|ρ| (default 1e-6)");
  command->add_option("--cutoff-hz", *cutoff, "keep only the modes below this frequency (default: all)");
  return [=] {
    if (*harmonics < 0 || *harmonics > 60) throw InputError(fmt::format("--harmonics {}: must be in [1, 60]", *harmonics));
    if (!(*tolerance > 0 && *tolerance < 1)) throw InputError(fmt::format("--tolerance {}: must be in (0, 1)", *tolerance));
    if (!(*cutoff >= 0)) throw InputError(fmt::format("--cutoff-hz {}: must be >= 0", *cutoff));
    const Scene scene = options->load();
    const BladeModel model = assemble_model(scene.blade, scene.model);
    const LoadSeries load = load_series(scene);
    if (!load.frequency_known) {
      throw InputError("operation.speed_rad_s = 0: the pulses have no frequency; give load.pulse_frequency_hz "
                       "(in Hz, > 0) or a speed > 0");
    }
    const PeriodicSystem sys = periodic_system(model, scene, load, *cutoff);
    const FloquetResult result = floquet_multipliers(sys, {parse_method(*method), *harmonics, *tolerance});
    print(*options, scene, model, sys, load, result);
  };
}

}  // namespace bladestab::cli
