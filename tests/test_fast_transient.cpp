// The fast transient method (exact_stepping.hpp): against RKF45 at a much tighter tolerance, against
// closed forms of free vibration, and the unstable run's growth against the Floquet multipliers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bladestab/base/constants.hpp"
#include "bladestab/blade/undamped_modes.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/transient/transient.hpp"
#include "bladestab/transient/transient_error.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

TransientResult run(const Scene& scene, TransientMethod method, double tolerance, double revolutions) {
  TransientOptions o;
  o.method = method;
  o.tolerance = o.contact_tolerance = tolerance;
  o.revolutions = revolutions;
  o.self_check = false;
  return run_transient(assemble_model(scene), scene, o);
}

// The fast method as a user runs it, with its self-check, over `revolutions`.
TransientResult checked_run(const Scene& scene, double revolutions) {
  TransientOptions o;
  o.revolutions = revolutions;
  const TransientResult r = run_transient(assemble_model(scene), scene, o);
  REQUIRE(r.self_check);
  return r;
}

// max |a − b| over the samples of the tip deflections, relative to the peak of b.
double history_difference(const TransientResult& a, const TransientResult& b) {
  REQUIRE(a.samples.size() == b.samples.size());
  double difference = 0, peak = 0;
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    const TransientSample &p = a.samples[k], &q = b.samples[k];
    REQUIRE(p.time_s == Approx(q.time_s).epsilon(1e-12));
    difference = std::max({difference, std::abs(p.tip_lateral_m - q.tip_lateral_m)});
    peak = std::max(peak, std::abs(q.tip_lateral_m));
  }
  return difference / peak;
}

// A run's error estimate, and the same quantities of the scene on `rich_terms` (the truth it is
// held against), over `revolutions`.
struct EstimateAndTruth {
  TransientErrorEstimate estimate;
  std::vector<TransientQuantity> truth;
};
EstimateAndTruth estimate_against(const Scene& scene, int rich_terms, double revolutions) {
  Scene rich = scene;
  rich.model.terms = rich_terms;
  TransientOptions o;
  o.revolutions = revolutions;
  const TransientResult r = run_transient(assemble_model(scene), scene, o);
  return {estimate_transient_error(scene, o, r), transient_quantities(run_transient(assemble_model(rich), rich, o))};
}

// The true pulse train's Floquet multipliers on the whole Ritz model of the scene: its monodromy
// through each contact (pulse_monodromy.hpp), independent of the transient's stepping.
FloquetResult true_train_floquet(const Scene& scene, const BladeModel& model, double tolerance) {
  Scene exact = scene;
  exact.load.approximation = LoadApproximation::exact;
  const PeriodicSystem whole = periodic_system(model, exact, load_series(exact), {ReductionKind::none, 0, 0});
  return pulse_train_multipliers(whole, periodic_pulse(pulse_train(exact)), {FloquetMethod::monodromy, 0, tolerance});
}

}  // namespace

TEST_CASE("fast transient: the history of RKF45 at rtol 1e-12 within 1e-10 of the peak", "[transient][fast][slow]") {
  // Two profiles, two pulses per revolution; with and without friction and each damping model.
  // Undamped, the contact comes from its first half (exact_stepping.hpp), also where the samples
  // cut it unevenly (t_c = 0.023 and 0.017 of a revolution: the middle between two samples).
  const std::vector<std::vector<std::string>> cases{
      {"load.profile=\"half-sine\"", "load.friction=0"},
      {"load.profile=\"half-sine\"", "load.friction=0.3", "load.contact_time_rev=0.023"},
      {"load.profile=\"cosine\"", "load.friction=0.1", "load.contact_time_rev=0.017"},
      {"load.profile=\"half-sine\"", "load.friction=0.3", "damping.model=\"modal\"", "damping.ratio=0.02"},
      {"load.profile=\"triangular\"", "load.friction=0.2", "damping.model=\"rayleigh\"", "damping.ratio=0.01",
       "damping.frequencies_hz=[60, 1300]"},
      {"load.profile=\"triangular\"", "load.friction=0", "damping.model=\"paper\"", "damping.ratio=0.01"},
  };
  for (const std::vector<std::string>& overrides : cases) {
    std::vector<std::string> all{"model.terms=6", "load.pulses_per_rev=2", "load.contact_time_rev=0.02"};
    all.insert(all.end(), overrides.begin(), overrides.end());
    const Scene scene = paper_scene(all);
    const TransientResult fast = run(scene, TransientMethod::fast, 1e-12, 1.5);
    const TransientResult reference = run(scene, TransientMethod::rkf45, 1e-12, 1.5);
    CAPTURE(overrides);
    CHECK(fast.method == TransientMethod::fast);
    CHECK(history_difference(fast, reference) < 1e-10);
  }
}

TEST_CASE("fast transient: the paper's damping, overdamping the stiffest modes, is an independent integration's history",
          "[transient][fast]") {
  // C = (2ζ/Ω) K_E (37) damps mode k by ζ ω_k/Ω: every mode above 4.8 kHz is overdamped. The free
  // flight's damping work must not go through e^{−Aᵀh}, whose growth e^{2ζω_k²h/Ω} over a sample
  // interval loses every digit at 8 terms and passes the double range from 10 terms on.
  const Scene scene = paper_scene({"model.terms=8", "damping.model=\"paper\"", "damping.ratio=0.01"});
  // Through the pulse and 0.02 revolution of free flight against the self-check's independent
  // integration at rtol 1e-10, and the damping's work in free flight against the energy balance E(t) − E(0) = W(t).
  const TransientResult fast = checked_run(scene, 0.04);
  CHECK(fast.self_check->reference == "rkf78");
  CHECK(fast.self_check->difference <= 1e-9);
  double energy = 0, balance = 0;
  for (const TransientSample& x : fast.samples) {
    energy = std::max(energy, x.kinetic_energy_j + x.strain_energy_j);
    balance = std::max(balance, std::abs(x.energy_balance_error_j));
  }
  CHECK(balance <= 1e-9 * energy);
  CHECK(fast.samples.back().work_j != fast.samples[fast.samples.size() - 2].work_j);  // the damping works
}

TEST_CASE("fast transient: one pulse in a period of many revolutions is RKF45's history", "[transient][fast]") {
  // pulse_frequency_hz = 1.5e-45: one contact at t = 0, then free flight for the rest of the run.
  // Times are told apart on their own scale (a free flight's length, an offset within the contact),
  // not on the pulse period's 6.5e44 s, which would take every interval for the first one.
  const Scene scene = paper_scene({"model.terms=4", "load.pulse_frequency_hz=1.5e-45"});
  const TransientResult fast = run(scene, TransientMethod::fast, 1e-12, 1);
  const TransientResult reference = run(scene, TransientMethod::rkf45, 1e-12, 1);
  CHECK(fast.method == TransientMethod::fast);
  CHECK(history_difference(fast, reference) < 1e-9);
}

TEST_CASE("fast transient: a fractional run's samples are RKF45's, the last at its end", "[transient][fast]") {
  // 0.3 of a revolution at 200 samples a revolution: samples 0..60, the 60th at 0.3 T exactly
  // (60 T/200 rounds past 0.3 T; RKF45, which ends at 0.3 T, once dropped it).
  const Scene scene = paper_scene({"model.terms=4"});
  const TransientResult fast = run(scene, TransientMethod::fast, 1e-10, 0.3);
  const TransientResult reference = run(scene, TransientMethod::rkf45, 1e-10, 0.3);
  REQUIRE(reference.samples.size() == 61);
  CHECK(reference.samples.back().time_s == Approx(0.3 * 2 * 3.14159265358979323846 / 300).epsilon(1e-14));
  CHECK(history_difference(fast, reference) < 1e-7);
}

TEST_CASE("fast transient: a run stopped within the self-check's stretch is checked to where it stopped",
          "[transient][fast]") {
  // A thick blade (slenderness 0.1) under F̄ = 5 leaves the elastic range within 0.005 revolution,
  // before the self-check's end at 0.03: the check compares with its reference at the stop instead.
  const Scene scene = paper_scene({"model.terms=4", "blade.slenderness=0.1", "model.coriolis=false"});
  const TransientResult r = checked_run(scene, 0.3);
  REQUIRE(r.stopped);
  CHECK(r.stopped->revolution < 0.03);
  CHECK(r.self_check->until_revolutions == Approx(r.stopped->revolution).epsilon(1e-12));
  CHECK(r.self_check->difference <= r.self_check->allowed);
  // Within a sample interval the linear response passes the range by orders of magnitude: no sample
  // beyond it is written (the axial change of 1 % strain is the first to go).
  const double L = assemble_model(scene).blade.L;
  for (const TransientSample& s : r.samples) {
    CHECK(std::abs(s.tip_lateral_m) <= 0.1 * L);
    CHECK(std::abs(s.tip_axial_m - r.samples.front().tip_axial_m) <= 0.01 * L);
  }
}

TEST_CASE("fast transient: free vibration of a one-term model is the exact cosine", "[transient][fast]") {
  // No load, no Coriolis coupling: each undamped mode swings as cos ωt about the equilibrium.
  const Scene scene = paper_scene({"model.terms=1", "model.coriolis=false", "load.fmax_over_fcr=0"});
  const BladeModel model = assemble_model(scene);
  const double speed = scene.operation.speed_rad_s;
  const UndampedModes modes = undamped_modes(model, speed);
  const int n = model.layout.size();
  for (int k = 0; k < n; ++k) {
    const Eigen::VectorXd shape = modes.shapes.col(k);
    Eigen::VectorXd start = rotating_equilibrium(model, speed);
    start.head(n) += 1e-3 * shape;
    TransientOptions o;
    o.revolutions = 2;
    o.initial_state = start;
    const TransientResult r = run_transient(model, scene, o);
    REQUIRE(r.method == TransientMethod::fast);
    const double omega = std::sqrt(modes.omega2(k)), tip = model.tip_lateral.dot(shape), axial = model.tip_axial.dot(shape);
    double worst = 0;
    for (const TransientSample& s : r.samples) {
      const double c = 1e-3 * std::cos(omega * s.time_s);
      worst = std::max({worst, std::abs(s.tip_lateral_m - c * tip) / (1e-3 * std::abs(tip) + 1e-300),
                        std::abs(s.tip_axial_m - r.static_tip_axial_m - c * axial) / (1e-3 * std::abs(axial) + 1e-300)});
    }
    CAPTURE(k, omega);
    CHECK(worst < 1e-9);
  }
}

TEST_CASE("fast transient: damped free vibration is the closed form", "[transient][fast]") {
  // Modal damping ζ without Coriolis coupling: mode k decays as e^{−ζωt}(cos ω_d t + ζ/√(1−ζ²) sin ω_d t).
  const double zeta = 0.05;
  const Scene scene = paper_scene({"model.terms=2", "model.coriolis=false", "load.fmax_over_fcr=0",
                                   "damping.model=\"modal\"", "damping.ratio=0.05"});
  const BladeModel model = assemble_model(scene);
  const double speed = scene.operation.speed_rad_s;
  const UndampedModes modes = undamped_modes(model, speed);
  const int n = model.layout.size();
  Eigen::VectorXd start = rotating_equilibrium(model, speed);
  start.head(n) += 1e-3 * modes.shapes.col(0);
  TransientOptions o;
  o.revolutions = 3;
  o.initial_state = start;
  const TransientResult r = run_transient(model, scene, o);
  const double w = std::sqrt(modes.omega2(0)), wd = w * std::sqrt(1 - zeta * zeta);
  const double tip = 1e-3 * model.tip_lateral.dot(modes.shapes.col(0));
  double worst = 0;
  for (const TransientSample& s : r.samples) {
    const double t = s.time_s;
    const double exact = tip * std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t));
    worst = std::max(worst, std::abs(s.tip_lateral_m - exact) / std::abs(tip));
  }
  CHECK(worst < 1e-9);
  // The damping's work (Van Loan's integral) balances the energy lost.
  double balance = 0;
  for (const TransientSample& s : r.samples) balance = std::max(balance, std::abs(s.energy_balance_error_j));
  CHECK(balance < 1e-9 * r.initial_vibration_energy_j);
}

TEST_CASE("fast transient: the unstable cosine load stops at the small-deflection range with the Floquet growth",
          "[transient][fast][long_under_sanitizers]") {
  // The paper's cosine load (42) at F̄ = 5, 300 rad/s, N = 8: max|ρ| = 2.1992274 (validation.md).
  const Scene scene = paper_scene({"model.terms=8", "load.profile=\"cosine\"", "load.contact_time_rev=1"});
  const BladeModel model = assemble_model(scene);
  Scene frequency = scene;
  frequency.load.approximation = LoadApproximation::cosine;
  const FloquetResult floquet = floquet_multipliers(periodic_system(model, frequency, load_series(frequency)),
                                                    {FloquetMethod::automatic, 0, 1e-8});
  TransientOptions o;
  o.revolutions = 14;
  const TransientResult r = run_transient(model, scene, o);
  REQUIRE(r.stopped);
  CHECK(r.stopped->revolution < 14);
  // The history ends at the last sample within the range, one sample interval (1/200 revolution)
  // before the stop.
  CHECK(std::abs(r.samples.back().tip_lateral_m) <= 0.1 * model.blade.L);
  CHECK(r.stopped->revolution == Approx(r.samples.back().revolutions + 1.0 / 200).epsilon(1e-12));
  REQUIRE(r.growth.omitted.empty());
  CHECK(r.growth.growth == Approx(floquet.max_abs_multiplier).margin(1e-4));
}

TEST_CASE("transient error estimate: the 12-term run's stated basis error covers its difference to 24 terms",
          "[transient][fast][slow]") {
  // The scene's half-sine train, one revolution: peaks and energy of N = 12 against N = 24 (Legendre
  // converges exponentially, so 24 terms stand in for the continuum to well below the 12-term error).
  const auto [e, truth] = estimate_against(paper_scene({"model.terms=12"}), 24, 1);
  REQUIRE(e.reference_terms == std::vector<int>{18});
  // The peaks, the energy, the axial mean, the axial peak and the growth (the revolution's change
  // carried on).
  REQUIRE(e.quantities.size() == 6);
  for (std::size_t k = 0; k < 6; ++k) {
    const double difference = std::abs(e.quantities[k].value - truth[k].value);
    CAPTURE(e.quantities[k].name, e.quantities[k].value, truth[k].value, e.quantities[k].budget.total());
    CHECK(difference <= e.quantities[k].budget.total());
    // Not vacuous: measured 2.5× (axial peak) to 14× (energy) the difference; 5.0× for the axial mean.
    if (k < 4) CHECK(e.quantities[k].budget.total() < 30 * difference + 1e-12 * std::abs(truth[k].value));
  }
}

TEST_CASE("transient error estimate: peaks that agree by chance between 8 and 12 terms are bounded by their revolutions'",
          "[transient][fast][slow]") {
  // 60 revolutions of the scene's train: the lateral peak is 1.36446e-4 m at 8 terms and 1.35503e-4 at
  // 12, 9.4e-7 apart, while 24 terms give 1.41961e-4 (32: 1.41941e-4), 5.5e-6 from 8 terms; the two
  // models' peaks of each revolution differ by up to 1.4e-5.
  const auto [e, truth] = estimate_against(paper_scene({"model.terms=8"}), 24, 60);
  REQUIRE(e.reference_terms == std::vector<int>{12});
  const TransientQuantity& lateral = e.quantities.front();
  REQUIRE(lateral.name == "peak_tip_lateral_m");
  const double difference = std::abs(lateral.value - truth.front().value);
  CAPTURE(lateral.value, truth.front().value, lateral.budget.basis);
  CHECK(difference > 5e-6);  // the case: the plain comparison's 3.3 × 9.4e-7 would not cover it
  CHECK(difference <= lateral.budget.total());
  CHECK(lateral.budget.total() < 5 * difference);
}

TEST_CASE("transient error estimate: the sine basis' estimate against 2N and 4N covers a 60-term run",
          "[transient][fast][slow][parallel]") {
  // The paper's model (sine basis, 10 terms), 20 revolutions of the scene's half-sine train. Its
  // lateral peak moves by 1.2 % from 10 to 20 terms and by 2.6 % more to 40: against 20 terms alone,
  // at the slowest trusted rate, the stated error would be 1.4× short of the 60-term run's distance.
  const Scene scene = paper_scene({"model.basis=\"sine\"", "model.terms=10"});
  Scene rich = scene;
  rich.model.terms = 60;
  TransientOptions o;
  o.revolutions = 20;
  o.threads = 2;
  const TransientResult r = run_transient(assemble_model(scene), scene, o);
  const TransientErrorEstimate e = estimate_transient_error(scene, o, r);
  REQUIRE(e.reference_terms == std::vector<int>{20, 40});
  o.self_check = false;
  const std::vector<TransientQuantity> truth = transient_quantities(run_transient(assemble_model(rich), rich, o));
  REQUIRE(e.quantities.size() == truth.size());
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const double difference = std::abs(e.quantities[k].value - truth[k].value);
    CAPTURE(e.quantities[k].name, e.quantities[k].value, truth[k].value, e.quantities[k].budget.total());
    CHECK(difference <= e.quantities[k].budget.total());
    // Not vacuous: measured 1.7× (energy, axial mean) to 9.6× (lateral peak) the difference.
    CHECK(e.quantities[k].budget.total() < 30 * difference + 1e-12 * std::abs(truth[k].value));
  }
}

TEST_CASE("transient error estimate: the richer runs beside the run give the estimate of the runs after it, on any "
          "number of threads", "[transient][fast][parallel]") {
  // Legendre (one richer model, 12 terms) and sine (two, 8 and 16 terms: two tasks beside the run).
  for (const char* basis : {"legendre", "sine"}) {
    const Scene scene = paper_scene({"model.terms=" + std::string(basis[0] == 's' ? "4" : "8"),
                                     "model.basis=\"" + std::string(basis) + "\""});
    const std::vector<BladeModel> richer = assemble_richer_models(scene);
    TransientOptions o;
    o.revolutions = 1;
    const TransientErrorEstimate after =
        estimate_transient_error(scene, o, run_transient(assemble_model(scene), scene, o));
    for (const int threads : {1, 2, 3}) {
      o.threads = threads;
      const EstimatedTransient beside = run_transient_with_error(assemble_model(scene), richer, scene, o);
      REQUIRE(beside.error);
      CHECK(beside.error->reference_terms == after.reference_terms);
      REQUIRE(beside.error->quantities.size() == after.quantities.size());
      for (std::size_t k = 0; k < after.quantities.size(); ++k) {
        CAPTURE(basis, threads, after.quantities[k].name);
        CHECK(beside.error->quantities[k].value == after.quantities[k].value);
        CHECK(beside.error->quantities[k].budget.total() == after.quantities[k].budget.total());
      }
    }
  }
}

namespace {

// max |a − b| over the samples of the tip's lateral deflection and of its axial vibration (about
// the static stretch), each relative to its peak in b (μ = 0 leaves the lateral tip at rest).
double clearance_history_difference(const TransientResult& a, const TransientResult& b) {
  REQUIRE(a.samples.size() == b.samples.size());
  double lateral = 0, axial = 0, lateral_peak = 0, axial_peak = 0;
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    const TransientSample &p = a.samples[k], &q = b.samples[k];
    REQUIRE(p.time_s == Approx(q.time_s).epsilon(1e-12));
    lateral = std::max(lateral, std::abs(p.tip_lateral_m - q.tip_lateral_m));
    axial = std::max(axial, std::abs(p.tip_axial_m - q.tip_axial_m));
    lateral_peak = std::max(lateral_peak, std::abs(q.tip_lateral_m));
    axial_peak = std::max(axial_peak, std::abs(q.tip_axial_m - b.static_tip_axial_m));
  }
  return std::max(lateral_peak > 0 ? lateral / lateral_peak : lateral, axial / axial_peak);
}

}  // namespace

TEST_CASE("fast transient in clearance mode: the history of RKF45 at rtol 1e-10 within 1e-6 of the peak",
          "[transient][fast][clearance][slow]") {
  // Appendix C's rub (3 mm clearance, 3.03 mm half-sine distortion once per revolution) through two
  // contacts, at 8 and at the scene's 16 terms, without and with friction.
  for (const std::string terms : {"8", "16"}) {
    for (const std::string friction : {"0", "0.2"}) {
      const Scene scene = paper_scene({"model.terms=" + terms, "load.mode=clearance", "load.intrusion=3.03e-3",
                                       "load.friction=" + friction});
      const BladeModel model = assemble_model(scene);
      TransientOptions o;
      o.revolutions = 1.5;
      const TransientResult fast = run_transient(model, scene, o);
      o.method = TransientMethod::rkf45;
      o.tolerance = 1e-10;
      const TransientResult reference = run_transient(model, scene, o);
      CAPTURE(terms, friction);
      REQUIRE(fast.method == TransientMethod::fast);
      REQUIRE(fast.self_check);
      CHECK(fast.self_check->difference <= fast.self_check->allowed);
      const double difference = clearance_history_difference(fast, reference);
      WARN("clearance, " << terms << " terms, μ = " << friction << ": history within " << difference
                         << " of the peak; peak force " << fast.contact->peak_force_n << " against "
                         << reference.contact->peak_force_n << " N");
      CHECK(difference < 1e-6);
      CHECK(fast.contact->closures == reference.contact->closures);
      CHECK(fast.contact->peak_force_n == Approx(reference.contact->peak_force_n).epsilon(1e-6));
      CHECK(fast.contact->contact_time_s == Approx(reference.contact->contact_time_s).epsilon(1e-6));
    }
  }
}

TEST_CASE("fast transient in clearance mode: a tip at rest against a still casing stays at rest, touching it",
          "[transient][fast][clearance]") {
  // Clearance 0, no distortion: the overlap is 0 all along the free flight and nothing moves the tip.
  const Scene scene = paper_scene({"model.terms=8", "load.mode=clearance", "load.clearance=0", "load.intrusion=0"});
  const TransientResult r = checked_run(scene, 2);
  REQUIRE(r.method == TransientMethod::fast);
  CHECK(r.contact->closures == 0);
  CHECK(r.contact->peak_force_n == 0);
  const Eigen::VectorXd equilibrium = rotating_equilibrium(assemble_model(scene), scene.operation.speed_rad_s);
  CHECK((r.final_state - equilibrium).norm() <= 1e-12 * equilibrium.norm());
  // No vibration: the self-check's difference is on the reference's resolution, and within it.
  CHECK(r.self_check->relative_to_resolution);
  CHECK(r.self_check->difference <= r.self_check->allowed);
}

TEST_CASE("fast transient: a short run's growth is the blade's, where its response has not yet shown it",
          "[transient][fast]") {
  // Rectangular pulses on 9 terms: the true train's max|ρ| is 1.0375 (its monodromy through the
  // contact), but over 10 revolutions the run's response barely grows (a fit over the run alone
  // gives 1 ± 1.2e-5). The last change carried on by the revolution's propagators reaches it.
  const Scene scene = paper_scene({"model.terms=9", "load.profile=rectangular"});
  const BladeModel model = assemble_model(scene);
  const FloquetResult floquet = true_train_floquet(scene, model, 1e-9);
  REQUIRE(floquet.max_abs_multiplier > 1.03);
  TransientOptions o;
  o.revolutions = 10;
  const TransientResult r = run_transient(model, scene, o);
  REQUIRE(r.growth.omitted.empty());
  CAPTURE(r.growth.growth - floquet.max_abs_multiplier, r.growth.error_estimate, floquet.error_estimate);
  CHECK(std::abs(r.growth.growth - floquet.max_abs_multiplier) <= r.growth.error_estimate + floquet.error_estimate);
  CHECK(r.growth.error_estimate < 1e-3);
}

TEST_CASE("transient error estimate: the casing contact's stated errors cover a 24-term run", "[transient][clearance]") {
  // Appendix C's rub at 8 terms, 2 revolutions: the contacts' count, time, peak force and deepest
  // overlap hang on the high modes (on the scene's 16 terms with a 4 mm bump the peak force moves
  // 2× between 12, 16 and 24 terms), so each is stated with its error against the richer models.
  const auto [e, truth] =
      estimate_against(paper_scene({"model.terms=8", "load.mode=\"clearance\"", "load.intrusion=3.03e-3"}), 24, 2);
  int contact_quantities = 0;
  for (const TransientQuantity& q : e.quantities) {
    if (q.name.rfind("contact_", 0) != 0) continue;
    ++contact_quantities;
    const auto same = std::find_if(truth.begin(), truth.end(), [&](const TransientQuantity& t) { return t.name == q.name; });
    REQUIRE(same != truth.end());
    CAPTURE(q.name, q.value, same->value, q.budget.total());
    CHECK(q.budget.unbounded.empty());
    CHECK(std::abs(q.value - same->value) <= q.budget.total());
  }
  CHECK(contact_quantities == 4);
}

TEST_CASE("fast transient: a run that ends inside a revolution carries on its last whole one, k³ of the pulse "
          "period's multiplier", "[transient][fast]") {
  // Three triangular pulses a revolution on 6 terms: the train grows by max|ρ|³ a revolution (its
  // monodromy over a pulse period). A run of 2.5 revolutions carries on its last whole revolution,
  // up to that revolution's end, where an output time sums to 2T only up to rounding.
  const Scene scene = paper_scene({"model.terms=6", "load.profile=triangular", "load.fmax_over_fcr=6",
                                   "load.contact_time_rev=0.02", "load.pulses_per_rev=3"});
  const BladeModel model = assemble_model(scene);
  const FloquetResult floquet = true_train_floquet(scene, model, 1e-10);
  const double per_revolution = std::pow(floquet.max_abs_multiplier, 3);
  REQUIRE(per_revolution > 1.1);
  for (const double revolutions : {2.0, 2.5}) {
    TransientOptions o;
    o.revolutions = revolutions;
    const TransientResult r = run_transient(model, scene, o);
    REQUIRE(r.growth.omitted.empty());
    CAPTURE(revolutions, r.growth.growth - per_revolution, r.growth.error_estimate);
    CHECK(std::abs(r.growth.growth - per_revolution) <= r.growth.error_estimate + 3 * floquet.error_estimate * per_revolution);
  }
}

TEST_CASE("fast transient without load: the state never changes, and the growth says so", "[transient][fast]") {
  // F̄ = 0 from the rotating equilibrium: nothing moves (every revolution's change is 0). The growth
  // said "0 whole revolutions; the fit needs 6" after six.
  const Scene scene = paper_scene({"load.fmax_over_fcr=0", "model.terms=8"});
  TransientOptions o;
  o.revolutions = 6;
  const TransientResult r = run_transient(assemble_model(scene), scene, o);
  REQUIRE(r.revolution_change.size() == 6);
  for (const double change : r.revolution_change) CHECK(change == 0);
  for (const TransientSample& s : r.samples) CHECK(s.tip_lateral_m == 0);
  CHECK_THAT(r.growth.omitted, Catch::Contains("did not change over its 6 whole revolutions"));
}

TEST_CASE("fast transient: pulses not locked to the revolution carry no revolution's propagators on", "[transient][fast]") {
  // 30 Hz pulses at 47.7 revolutions a second: no two revolutions see the same pulses, so the last
  // one's propagators say nothing of the next (they gave 1 ± 1e-10 here). The true train's max|ρ|
  // per pulse period, 1.105, is 1.105^(T_rev/T_p) ≈ 1.065 a revolution: the growth the run states,
  // if it states one, covers it.
  const Scene scene =
      paper_scene({"model.terms=8", "load.profile=rectangular", "load.contact_time_rev=0.05", "load.pulse_frequency_hz=30"});
  const BladeModel model = assemble_model(scene);
  const FloquetResult floquet = true_train_floquet(scene, model, 1e-6);
  const double per_revolution =
      std::pow(floquet.max_abs_multiplier, 2 * M_PI / scene.operation.speed_rad_s * 30);
  REQUIRE(per_revolution > 1.05);
  TransientOptions o;
  o.revolutions = 20;
  const TransientResult r = run_transient(model, scene, o);
  CAPTURE(r.growth.growth, r.growth.error_estimate, r.growth.omitted, per_revolution);
  CHECK(r.continued_log_change.empty());
  CHECK((!r.growth.omitted.empty() || std::abs(r.growth.growth - per_revolution) <= r.growth.error_estimate));
}

TEST_CASE("transient error estimate: in clearance mode the method part is measured, and covers RKF45 at 1e-9",
          "[transient][clearance][slow]") {
  // Three triangular bumps 3.5 mm deep a revolution with μ = 0.3 on 8 terms, 4 revolutions: ~100
  // contacts through which a time-stepping error grows. At the default tolerances the peak contact
  // force is 19.0 MN, against 14.7–14.8 MN at 1/10 of them and by RKF45; the propagators' bound alone
  // said 0.06 N. Measured against the run at 1/100 of the tolerances, the part covers RKF45's.
  const Scene scene = paper_scene({"model.terms=8", "load.mode=clearance", "load.intrusion=0.0035",
                                   "load.pulses_per_rev=3", "load.friction=0.3", "load.profile=triangular"});
  const BladeModel model = assemble_model(scene);
  TransientOptions o;
  o.revolutions = 4;
  const TransientResult fast = run_transient(model, scene, o);
  const TransientErrorEstimate e = estimate_transient_error(scene, o, fast);
  TransientOptions rkf45 = o;
  rkf45.method = TransientMethod::rkf45;
  rkf45.tolerance = 1e-9;
  const std::vector<TransientQuantity> reference = transient_quantities(run_transient(model, scene, rkf45));
  for (const std::string name : {"contact_peak_force_n", "contact_max_overlap_m", "peak_tip_lateral_m"}) {
    const auto ours = std::find_if(e.quantities.begin(), e.quantities.end(), [&](const TransientQuantity& q) { return q.name == name; });
    const auto theirs = std::find_if(reference.begin(), reference.end(), [&](const TransientQuantity& q) { return q.name == name; });
    REQUIRE(ours != e.quantities.end());
    REQUIRE(theirs != reference.end());
    CAPTURE(name, ours->value, theirs->value, ours->budget.method, ours->budget.total());
    CHECK(std::abs(ours->value - theirs->value) <= ours->budget.total());
    CHECK(std::abs(ours->value - theirs->value) <= 2 * ours->budget.method);
  }
}
