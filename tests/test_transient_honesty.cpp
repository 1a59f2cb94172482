// Transient honesty (issue 8, item 5): a loose tolerance cannot make the stepper unstable, a run
// that breaks its energy balance or leaves the small-deflection model is an error, and the growth
// per revolution is reported only where a fit means something, whatever the output sampling.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/transient/transient.hpp"
#include "bladestab/transient/transient_checks.hpp"
#include "bladestab/transient/transient_error.hpp"
#include "support/json.hpp"
#include "support/run_cli.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

// The largest difference of a tip history from a reference one, relative to the reference's peak.
double history_difference(const TransientResult& r, const TransientResult& reference, double TransientSample::*field) {
  double peak = 0, d = 0;
  for (std::size_t k = 0; k < reference.samples.size(); ++k) {
    peak = std::max(peak, std::abs(reference.samples[k].*field));
    d = std::max(d, std::abs(r.samples.at(k).*field - reference.samples[k].*field));
  }
  return d / peak;
}

struct CliRun {
  int status = 0;  // as returned by std::system
  std::string out, err;
  bool wrote_csv = false;
};

// `bladestab transient` on the paper scene with `options` (shell words), in a scratch directory.
CliRun run_transient_cli(const std::string& options) {
  // In this process's private scratch directory: ctest runs the CLI tests side by side.
  const std::filesystem::path dir = testing_support::scratch() / "transient_honesty";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string command = std::string("exec '") + BLADESTAB_EXE + "' transient '" + testing_support::paper_scene_path() +
                              "' " + options + " --chart none --out '" + dir.string() + "' </dev/null >'" +
                              (dir / "stdout").string() + "' 2>'" + (dir / "stderr").string() + "'";
  const auto read = [](const std::filesystem::path& p) {
    std::ostringstream text;
    text << std::ifstream(p).rdbuf();
    return text.str();
  };
  CliRun run;
  run.status = std::system(command.c_str());
  run.out = read(dir / "stdout");
  run.err = read(dir / "stderr");
  run.wrote_csv = std::filesystem::exists(dir / "transient.csv");
  std::filesystem::remove_all(dir);
  return run;
}

// A failure as the CLI states one: exit 1, one line on stderr, nothing on stdout, no history written.
void check_one_line_failure(const CliRun& run) {
  INFO("stderr: " << run.err);
  REQUIRE(WIFEXITED(run.status));
  CHECK(WEXITSTATUS(run.status) == 1);
  CHECK(run.out.empty());
  CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
  CHECK(!run.wrote_csv);
}

}  // namespace

TEST_CASE("tolerance 1e-2 on the issue's run: the capped steps stay stable and match a tight-tolerance run", "[transient][honesty][slow]") {
  // The scene as shipped (N = 16, stiffest mode 158 kHz), the endless F̄ = 5 pulse train, 2 revolutions:
  // before the cap this run printed a lateral peak of 2.15e21 mm.
  const Scene s = paper_scene();
  const BladeModel m = assemble_model(s);
  TransientOptions loose, tight;
  loose.revolutions = tight.revolutions = 2;
  loose.tolerance = 1e-2;
  tight.tolerance = 1e-6;
  const TransientResult a = run_transient(m, s, loose), b = run_transient(m, s, tight);
  INFO("steps at 1e-2: " << a.steps.accepted << ", largest " << a.steps.largest_step << " s; cap " << a.fixed.step_s << " s");
  CHECK(a.steps.largest_step <= a.fixed.step_s * (1 + 1e-12));
  CHECK(a.fixed.parasitic_growth < 1.01);
  CHECK(history_difference(a, b, &TransientSample::tip_lateral_m) < 1e-6);  // measured 1.4e-9
  CHECK(history_difference(a, b, &TransientSample::tip_axial_m) < 1e-6);    // measured 2.2e-8
}

TEST_CASE("the energy balance E(t) - E(0) = W(t) holds with friction, damping and the follower load", "[transient][honesty][long_under_sanitizers]") {
  // The work W integrates the power of each force term separately from the state; E is computed from
  // the state. Only the right power formula closes the balance: every load term is on here (one F̄ = 5
  // pulse, μ = 0.2, modal damping ζ = 2 %, follower correction), from 1 mm of bending mode 1.
  const Scene s = paper_scene({"model.terms=8", "load.pulse_count=1", "load.friction=0.2", "damping.model=modal",
                               "damping.ratio=0.02"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 1;
  o.tolerance = 1e-9;
  o.follower = true;
  o.initial_state = rotating_equilibrium(m, 300);
  const Eigen::VectorXd mode1 =
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(m.stiffness(300), m.M).eigenvectors().col(0);
  o.initial_state->head(mode1.size()) += 1e-3 / m.tip_lateral.dot(mode1) * mode1;
  const TransientResult r = run_transient(m, s, o);
  const TransientChecks c = check_transient(r);
  double dissipated = 0;  // the damping and friction take energy out: W ends below its largest value
  for (const TransientSample& p : r.samples) dissipated = std::max(dissipated, p.work_j - r.samples.back().work_j);
  INFO("vibration energy " << c.vibration_energy_j << " J, balance error " << c.energy_error_j << " J, W(end) "
                           << r.samples.back().work_j << " J");
  INFO("dissipated " << dissipated << " J");
  CHECK(dissipated > 1e-2 * c.vibration_energy_j);           // the non-conservative terms act (measured 220 of 224 J)
  CHECK(c.energy_error_j < 1e-7 * c.vibration_energy_j);     // measured 5e-12
  CHECK(!transient_failure(c, s.blade.length));
}

TEST_CASE("the energy check flags the paper's literal fixed step, whose parasitic growth it cannot see itself", "[transient][honesty][long_under_sanitizers]") {
  // (54) taken literally, 8 steps per period of the stiffest (64 kHz) mode: RKF45 amplifies that mode
  // by |R(iπ/4)| = 1 + 1.7e-4 per step, ×1e7 over 7 revolutions of the F̄ = 5 pulse train. The chosen
  // step (n = 33 here) is the control.
  const Scene s = paper_scene({"model.terms=8"});
  const BladeModel m = assemble_model(s);
  TransientOptions literal, chosen;
  literal.revolutions = chosen.revolutions = 7;
  literal.adaptive = chosen.adaptive = false;
  literal.steps_per_period = 8;
  const TransientChecks bad = check_transient(run_transient(m, s, literal)), good = check_transient(run_transient(m, s, chosen));
  INFO("balance error: literal step " << bad.energy_error_j << " J, chosen step " << good.energy_error_j << " J, of "
                                      << good.vibration_energy_j << " J");
  const auto failure = transient_failure(bad, s.blade.length);
  REQUIRE(failure);
  CHECK(failure->integration);
  CHECK(bad.energy_error_j > 1e-2 * bad.vibration_energy_j);   // measured 5.3e-2 (26 of 500 J)
  CHECK(good.energy_error_j < 1e-5 * good.vibration_energy_j); // measured 2.4e-7
  CHECK(!transient_failure(good, s.blade.length));
  // The physical scale is the same in both: what the loads put in does not depend on the step.
  CHECK(bad.vibration_energy_j == Approx(good.vibration_energy_j).epsilon(1e-2));
}

TEST_CASE("a response growing past 0.1 L is outside the small-deflection model: an error, not a result", "[transient][honesty][long_under_sanitizers]") {
  // The cosine load (42) at F̄ = 5 is parametrically unstable, max|ρ| = 2.199 per revolution. From 1 mm
  // of bending mode 1 the tip passes 0.1 L = 100 mm after ln(100)/ln(2.199) ≈ 5.8 revolutions.
  const Scene s = paper_scene({"model.terms=8", "load.profile=cosine", "load.contact_time_rev=1"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.tolerance = 1e-6;
  o.initial_state = rotating_equilibrium(m, 300);
  const Eigen::VectorXd mode1 =
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(m.stiffness(300), m.M).eigenvectors().col(0);
  o.initial_state->head(mode1.size()) += 1e-3 / m.tip_lateral.dot(mode1) * mode1;
  o.revolutions = 8;
  o.max_lateral_over_length = HUGE_VAL;  // the check itself is tested, not the run's stop at 0.1 L
  const TransientResult r = run_transient(m, s, o);
  TransientResult first_four = r;  // the same run cut at 4 revolutions, where the tip is still at 24 mm
  first_four.samples.resize(4 * o.samples_per_revolution + 1);
  REQUIRE(first_four.samples.back().revolutions == Approx(4));
  const TransientChecks c = check_transient(r), c4 = check_transient(first_four);
  const auto failure = transient_failure(c, s.blade.length);
  INFO("peak lateral " << c4.peak_lateral_m << " m in 4 revolutions, " << c.peak_lateral_m << " m in 8; energy error "
                       << c.energy_error_j << " J of " << c.vibration_energy_j << " J");
  CHECK(c.energy_error_j < 1e-5 * c.vibration_energy_j);  // the integration itself is sound (measured 3e-13)
  CHECK(!transient_failure(c4, s.blade.length));
  REQUIRE(failure);
  CHECK(!failure->integration);
  // 1 mm × 2.199⁴ = 23 mm and × 2.199⁸ = 0.55 m (measured 24 mm, 0.62 m), within a factor 2 (the start
  // also excites the decaying multipliers and the forced response)
  CHECK(c4.peak_lateral_m > 0.0117);
  CHECK(c4.peak_lateral_m < 0.047);
  CHECK(c.peak_lateral_m > 0.27);
  CHECK(c.peak_lateral_m < 1.1);
}

TEST_CASE("growth per revolution: the Floquet max|rho| under the cosine load, whatever the output sampling", "[transient][honesty][slow]") {
  // The cosine load (42) as a true load, F̄ = 5, 8 revolutions from 1 µm of bending mode 1. The load
  // itself seeds the instability through the Coriolis coupling of the axial motion, and by revolution
  // 8 the tip passes 1 m: a run stops at 0.1 L by default (see below), but the model is linear, so the
  // growth is still its max|ρ|. Reference: the Floquet max|ρ| of the same model, 2.1992274
  // (monodromy at rtol 1e-12, README; the converged N = 10 model gives 2.1992297, 1e-6 away).
  const Scene s = paper_scene({"model.terms=8", "load.profile=cosine", "load.contact_time_rev=1"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 8;
  o.tolerance = 1e-6;
  o.initial_state = rotating_equilibrium(m, 300);
  const Eigen::VectorXd mode1 =
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(m.stiffness(300), m.M).eigenvectors().col(0);
  o.initial_state->head(mode1.size()) += 1e-6 / m.tip_lateral.dot(mode1) * mode1;
  o.max_lateral_over_length = HUGE_VAL;
  // RKF45 lands on the samples without changing its steps' results; the fast method's contact
  // pieces end at the samples, which moves its growth within its tolerance (exact_stepping.hpp).
  o.method = TransientMethod::rkf45;
  const TransientResult a = run_transient(m, s, o);
  o.samples_per_revolution = 37;
  const TransientResult b = run_transient(m, s, o);
  INFO("growth " << a.growth.growth << " ± " << a.growth.standard_error << " (ln); with 37 samples per revolution "
                 << b.growth.growth << "; " << a.growth.omitted);
  REQUIRE(a.growth.omitted.empty());
  CHECK(a.growth.growth == Approx(2.1992274).epsilon(2e-4));  // measured 6.7e-5
  CHECK(a.growth.standard_error < 1e-3);  // measured 3.4e-5
  // The fit uses the states at whole revolutions, where the integration ends: the output sampling
  // does not enter.
  REQUIRE(b.growth.omitted.empty());
  CHECK(b.growth.growth == Approx(a.growth.growth).epsilon(1e-12));
}

TEST_CASE("growth per revolution of a 2-revolution run: the fast method carries its change on, RKF45 omits it",
          "[transient][honesty][long_under_sanitizers]") {
  const Scene s = paper_scene({"model.terms=6", "load.profile=cosine", "load.contact_time_rev=1"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 2;
  o.tolerance = 1e-6;
  // The last revolution's change carried on by its propagators reaches the dominant multiplier of the
  // revolution map: Floquet's on the same model (the cosine load (42) is the train's one harmonic).
  Scene frequency = s;
  frequency.load.approximation = LoadApproximation::cosine;
  const FloquetResult floquet = floquet_multipliers(periodic_system(m, frequency, load_series(frequency)),
                                                    {FloquetMethod::automatic, 0, 1e-8});
  const TransientResult fast = run_transient(m, s, o);
  CHECK(fast.revolution_change.size() == 2);
  REQUIRE(fast.growth.omitted.empty());
  CHECK(std::abs(fast.growth.growth - floquet.max_abs_multiplier) <= fast.growth.error_estimate);
  CHECK(fast.growth.error_estimate < 1e-3);
  o.method = TransientMethod::rkf45;
  const TransientResult rkf45 = run_transient(m, s, o);
  CHECK(rkf45.growth.omitted == "2 whole revolutions; the fit needs 6");
}

TEST_CASE("fit_growth: an exact exponential, a beat that is no exponential, too few revolutions", "[transient][honesty]") {
  std::vector<double> clean, beating;
  for (int k = 0; k < 12; ++k) {
    clean.push_back(3e-6 * std::pow(2.2, k));
    beating.push_back(1 + 0.5 * std::cos(2.0 * k));  // steady on average, but no exponential
  }
  const GrowthFit a = fit_growth(clean), b = fit_growth(beating);
  CHECK(a.omitted.empty());
  CHECK(a.growth == Approx(2.2).epsilon(1e-12));
  CHECK(a.standard_error < 1e-12);
  CHECK(b.omitted.rfind("not a steady exponential", 0) == 0);
  CHECK(b.standard_error > 1e-2);
  clean.resize(5);
  CHECK(fit_growth(clean).omitted == "5 whole revolutions; the fit needs 6");
}

TEST_CASE("the CLI: a run that broke its energy balance is a one-line error with exit 1, and writes nothing", "[transient][honesty][long_under_sanitizers]") {
  // The paper's literal step over 7 revolutions (the broken run above).
  const CliRun run = run_transient_cli("--set model.terms=8 --revolutions 7 --step fixed --steps-per-period 8");
  check_one_line_failure(run);
  CHECK(run.err.find("8 steps per stiffest period, 7 revolutions): the energy balance broke") != std::string::npos);
  CHECK(run.err.find("leave out --steps-per-period") != std::string::npos);
}

TEST_CASE("the CLI: a contact the damping makes too stiff for the Magnus ladder is one line with exit 1, and writes "
          "nothing", "[transient][honesty]") {
  // The paper's damping (37) at 30 rad/s and ζ = 0.05 damps the stiffest mode by ζω/Ω ≈ 1700: a contact
  // piece needs ~1.7e6 steps for h‖A‖₁ ≤ 2, past the ladder's 65536 (the self-check running beside the
  // fast run stops with it).
  const CliRun run = run_transient_cli("--set damping.model=paper --set damping.ratio=0.05 "
                                       "--set operation.speed_rad_s=30 --revolutions 3");
  check_one_line_failure(run);
  CHECK(run.err.find("Magnus steps (h‖A‖₁ ≤ 2 with ‖A‖₁ = 3.31e+09/s") != std::string::npos);
  CHECK(run.err.find("use fewer terms or a lighter damping") != std::string::npos);
}

TEST_CASE("the CLI: a motion the load cannot excite is 0 with an error of 0 and no dominant frequency",
          "[transient][honesty]") {
  // Without the Coriolis coupling the lateral equations do not see the axial pulse (it enters them
  // only through G v, and v starts at rest): the lateral tip stays exactly at 0 on every model.
  const CliRun run = run_transient_cli("--set model.coriolis=false --set model.terms=6 --revolutions 2 --format json");
  INFO("stderr: " << run.err);
  REQUIRE(WIFEXITED(run.status));
  CHECK(WEXITSTATUS(run.status) == 0);
  CHECK(run.out.find("\"tip_lateral\": null,") != std::string::npos);
  CHECK(run.out.find("\"peak_tip_lateral_m\": 0,") != std::string::npos);
  // Without the axial field the axial pulse moves nothing: the self-check compares rest with rest.
  const CliRun still = run_transient_cli("--set model.axial=false --set model.terms=6 --revolutions 2 --format json");
  INFO("stderr: " << still.err);
  REQUIRE(WIFEXITED(still.status));
  CHECK(WEXITSTATUS(still.status) == 0);
  CHECK(still.out.find("\"relative_difference\": 0,") != std::string::npos);
}

TEST_CASE("the CLI: a feather touch is the light rub scaled, its checks held to the rounding of the static state",
          "[transient][honesty]") {
  // The response is linear in the load up to the parametric term F G (f − f_eq), second order in F̄:
  // at F̄ = 1e-5 and 1e-9 the peaks per unit F̄ agree to 6e-9 (lateral) and 5e-7 (axial: the difference
  // of two ~2 mm numbers at 1e-9, 3.5e-13 m apart). At 1e-9 the vibration energy
  // (~2e-13 J) lies below the rounding of E (a few ε of the ~1e3 J static terms), and the
  // vibration below RKF78's tolerance of the whole state: both checks allow for that, and the
  // spectrum of the static axial stretch plus a 1e-13-relative vibration still finds its mode.
  const auto peaks = [](const std::string& fbar) {
    const CliRun run = run_transient_cli("--set model.terms=6 --revolutions 2 --format json --digits full --no-error-estimate "
                                         "--set load.fmax_over_fcr=" + fbar);
    INFO("F̄ = " << fbar << ", stderr: " << run.err);
    REQUIRE(WIFEXITED(run.status));
    REQUIRE(WEXITSTATUS(run.status) == 0);
    const testing_support::Json j = testing_support::parse_json(run.out);
    CHECK(j["dominant_frequency_hz"]["tip_axial"].type == testing_support::Json::Type::number);
    return std::pair{j["peak_tip_lateral_m"].number, j["peak_tip_axial_m"].number - j["static_tip_axial_m"].number};
  };
  const auto [lateral_light, axial_light] = peaks("1e-5");
  const auto [lateral_feather, axial_feather] = peaks("1e-9");
  CHECK(lateral_feather * 1e4 == Approx(lateral_light).epsilon(1e-6));
  CHECK(axial_feather * 1e4 == Approx(axial_light).epsilon(1e-5));
}

TEST_CASE("the CLI: a 2-revolution RKF45 run gives growth_per_revolution null and says why", "[transient][honesty]") {
  const CliRun run = run_transient_cli("--set model.terms=6 --revolutions 2 --method rkf45 --format json");
  INFO("stderr: " << run.err);
  REQUIRE(WIFEXITED(run.status));
  CHECK(WEXITSTATUS(run.status) == 0);
  CHECK(run.out.find("\"growth_per_revolution\": null,") != std::string::npos);
  CHECK(run.out.find("\"growth_per_revolution_omitted\": \"2 whole revolutions; the fit needs 6\"") != std::string::npos);
  CHECK(run.wrote_csv);
}

TEST_CASE("the CLI: an unstable run is a result: it stops at the small-deflection range, writes its history, exit 0",
          "[transient][honesty][long_under_sanitizers]") {
  // The cosine load (42) at F̄ = 5 grows ×2.1992274 per revolution (N = 8): from the equilibrium the
  // tip passes 0.1 L in revolution 5.
  const CliRun run = run_transient_cli(
      "--set model.terms=8 --set load.profile=cosine --set load.contact_time_rev=1 --revolutions 14 --format json");
  INFO("stderr: " << run.err);
  REQUIRE(WIFEXITED(run.status));
  CHECK(WEXITSTATUS(run.status) == 0);
  CHECK(run.out.find("\"stopped\": {") != std::string::npos);
  CHECK(run.out.find("passed the small-deflection range of 0.1 L") != std::string::npos);
  // The growth as printed, to its whole error, which covers the distance to the Floquet value.
  const testing_support::Json j = testing_support::parse_json(run.out);
  const double growth = j["growth_per_revolution"].number, error = j["error_estimate"]["growth_per_revolution"].number;
  CAPTURE(growth, error);
  CHECK(std::abs(growth - 2.1992274) <= 1.5 * error);
  CHECK(error < 1e-3);
  CHECK(run.wrote_csv);
}

TEST_CASE("the CLI: by default each tip peak comes with its whole error, printed to the digits it supports, and a much "
          "richer model lies within it", "[transient][honesty][slow]") {
  // 12 terms, one revolution of the scene's half-sine train, against 30 terms (Legendre: far closer
  // to the continuum than the 12-term error), integrated in this process without the CLI.
  const CliRun run = run_transient_cli("--set model.terms=12 --revolutions 1 --format json");
  INFO("stderr: " << run.err);
  REQUIRE(WIFEXITED(run.status));
  REQUIRE(WEXITSTATUS(run.status) == 0);
  const testing_support::Json j = testing_support::parse_json(run.out);
  const Scene rich = paper_scene({"model.terms=30"});
  TransientOptions o;
  o.revolutions = 1;
  o.self_check = false;
  const std::vector<TransientQuantity> truth = transient_quantities(run_transient(assemble_model(rich), rich, o));
  const std::pair<const char*, std::size_t> printed[] = {{"peak_tip_lateral_m", 0}, {"mean_tip_axial_m", 3}};
  for (const auto& [name, index] : printed) {
    const double value = j[name].number, error = j["error_estimate"][name].number;
    CAPTURE(name, value, error, truth[index].value);
    // Covered: the estimate bounds the computed value's error; printing moves it by at most half a
    // unit of the error's decade.
    CHECK(std::abs(value - truth[index].value) <= 1.5 * error);
    // No digit below the error's decade.
    const double unit = std::pow(10.0, std::floor(std::log10(error)));
    CHECK(std::abs(value / unit - std::round(value / unit)) < 1e-6);
  }
  const CliRun without = run_transient_cli("--set model.terms=12 --revolutions 1 --no-error-estimate");
  CHECK(without.out.find("error      not estimated (--no-error-estimate)") != std::string::npos);
}

TEST_CASE("a fixed-step run states no error of its own: its estimate bounds none of its quantities",
          "[transient][honesty]") {
  // Its error is the step's, not a tolerance's: 4.7e-7 of the axial peak at 1/33 of the stiffest
  // period, 1.0e-3 at the paper's literal 1/8 (validation.md), where a tolerance would claim 1e-8.
  const Scene scene = paper_scene({"model.terms=6"});
  TransientOptions o;
  o.revolutions = 1;
  o.method = TransientMethod::rkf45;
  o.adaptive = false;
  const TransientErrorEstimate e = estimate_transient_error(scene, o, run_transient(assemble_model(scene), scene, o));
  REQUIRE_FALSE(e.quantities.empty());
  for (const TransientQuantity& q : e.quantities) {
    CAPTURE(q.name);
    REQUIRE(q.budget.unbounded.size() == 1);
    CHECK(q.budget.unbounded.front().find("the fixed step (--step fixed) states no error") != std::string::npos);
  }
}

TEST_CASE("the CLI: a fast run in contact throughout says its energy balance checks nothing", "[transient][honesty]") {
  // Two pulses a revolution, each half a revolution long: no free flight, where alone the fast method
  // balances the energy (in contact the work is the energy's change), so no balance is reported.
  const CliRun run = run_transient_cli("--set model.terms=4 --set load.pulses_per_rev=2 --set load.contact_time_rev=0.5 "
                                       "--revolutions 1 --no-error-estimate --format json");
  INFO("stderr: " << run.err);
  REQUIRE(WIFEXITED(run.status));
  CHECK(WEXITSTATUS(run.status) == 0);
  const testing_support::Json j = testing_support::parse_json(run.out);
  CHECK(j["energy_balance"]["max_error_j"].type == testing_support::Json::Type::null);
  CHECK(j["energy_balance"]["unchecked"].text.find("in contact throughout") != std::string::npos);
}
