// Time domain: energy conservation, agreement with the Floquet multipliers, the paper's Fig. 10/11
// single-pulse response, fixed against adaptive steps.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>

#include "bladestab/constants.hpp"
#include "bladestab/crosscheck.hpp"
#include "bladestab/damping.hpp"
#include "bladestab/modes.hpp"
#include "bladestab/response_analysis.hpp"
#include "bladestab/transient.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

// Undamped, non-gyroscopic modes of K(Ω), M-normalized; column k is mode k (ascending).
Eigen::MatrixXd modes_of(const BladeModel& m, double speed) {
  return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(m.stiffness(speed), m.M).eigenvectors();
}

// Equilibrium plus a tip displacement `bend` in the first bending mode and `stretch` in the first
// axial mode (the lowest modes whose tip motion is lateral or axial).
Eigen::VectorXd perturbed_equilibrium(const BladeModel& m, double speed, double bend, double stretch) {
  Eigen::VectorXd x = rotating_equilibrium(m, speed);
  const Eigen::MatrixXd phi = modes_of(m, speed);
  bool bent = false, stretched = false;
  for (Eigen::Index k = 0; k < phi.cols(); ++k) {
    const Eigen::VectorXd v = phi.col(k);
    const double lat = m.tip_lateral.dot(v), ax = m.tip_axial.dot(v);
    if (!bent && std::abs(lat) > std::abs(ax)) x.head(v.size()) += bend / lat * v, bent = true;
    else if (!stretched && std::abs(ax) > std::abs(lat)) x.head(v.size()) += stretch / ax * v, stretched = true;
  }
  return x;
}

// The largest change of the total energy over the run, and the largest kinetic energy (the scale
// of the vibration).
std::pair<double, double> energy_drift(const TransientResult& r) {
  const double e0 = r.samples.front().total_energy_j;
  double drift = 0, swing = 0;
  for (const TransientSample& p : r.samples) {
    drift = std::max(drift, std::abs(p.total_energy_j - e0));
    swing = std::max(swing, p.kinetic_energy_j);
  }
  return {drift, swing};
}

}  // namespace

TEST_CASE("undamped free vibration at 300 rad/s conserves the rotating-frame energy", "[transient]") {
  const Scene s = paper_scene({"model.terms=8", "load.fmax_over_fcr=0"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 10;
  o.tolerance = 1e-10;
  o.initial_state = perturbed_equilibrium(m, 300, 1e-3, 1e-4);
  const TransientResult r = run_transient(m, s, o);
  const auto [drift, swing] = energy_drift(r);
  INFO("energy " << r.samples.front().total_energy_j << " J, kinetic energy up to " << swing << " J, steps " << r.steps.accepted);
  CHECK(swing > 0.1);                   // it really vibrates
  CHECK(drift < 1e-8 * std::abs(swing)); // relative to the vibration energy
  CHECK(r.static_tip_axial_m == Approx(2.0e-3).epsilon(0.02));
}

TEST_CASE("growth per revolution under the periodic cosine load equals the Floquet max|rho|", "[transient][slow]") {
  // The paper's continuous cosine load (42) in the time domain: profile cosine over a whole revolution.
  const Scene s = paper_scene({"model.terms=8", "load.profile=cosine", "load.contact_time_rev=1"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 16;  // growth ×2.2 per revolution: 2.2¹⁶ ≈ 3e5 times the 1 µm start
  o.tolerance = 1e-9;
  o.samples_per_revolution = 400;
  o.initial_state = perturbed_equilibrium(m, 300, 1e-6, 0);
  const TransientResult r = run_transient(m, s, o);
  // Peak lateral tip deflection per revolution; the ratio of the last ones is the growth.
  std::vector<double> peak(16, 0);
  for (const TransientSample& p : r.samples) {
    const int rev = std::min(15, static_cast<int>(p.revolutions));
    peak[rev] = std::max(peak[rev], std::abs(p.tip_lateral_m));
  }
  const double growth = std::pow(peak[15] / peak[10], 1.0 / 5);
  INFO("peaks " << peak[10] << " … " << peak[15]);
  CHECK(growth == Approx(2.1992274).epsilon(0.01));
}

TEST_CASE("the paper's Fig. 10/11 single pulse: mode-1 lateral response, 2 mm stretch, first axial line", "[transient][paper]") {
  const Scene s = paper_scene({"model.terms=8", "load.pulse_count=1"});  // half-sine, F̄ = 5, t̄c = 0.01, μ = 0
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 20;
  o.tolerance = 1e-7;
  const TransientResult r = run_transient(m, s, o);
  std::vector<double> lat, ax;
  for (const TransientSample& p : r.samples) lat.push_back(p.tip_lateral_m), ax.push_back(p.tip_axial_m);
  const double rate = 200 * 300 / (2 * 3.14159265358979323846);
  const Spectrum lateral = amplitude_spectrum(lat, rate), axial = amplitude_spectrum(ax, rate);
  // First coupled bending mode of the same model, from the gyroscopic eigenproblem.
  const ModalSolution modes = solve_modes(m, system_at(m, 300, damping_matrix(m, s.damping, 300)), 300, 6, EigenSolverKind::dense);
  double f_axial = 0;
  for (const Mode& mode : modes.modes) if (mode.family == ModeFamily::axial && f_axial == 0) f_axial = mode.frequency_hz;
  CHECK(dominant_frequency(lateral) == Approx(modes.modes[0].frequency_hz).epsilon(0.003));
  CHECK(dominant_frequency(axial, 600) == Approx(f_axial).epsilon(0.003));
  CHECK(f_axial == Approx(1280).epsilon(0.001));
  double mean = 0;
  for (double a : ax) mean += a / ax.size();
  CHECK(mean == Approx(2.0e-3).epsilon(0.02));
  REQUIRE(r.growth.omitted.empty());
  CHECK(r.growth.growth == Approx(1).epsilon(0.01));  // undamped, one pulse: steady
}

// The paper's step (54), 8 steps per period of the stiffest (64 kHz) mode, lets RKF45's parasitic
// growth amplify that mode ×1.1e4 in 5 revolutions (measured: 1.7e-3 of the lateral peak apart);
// the chosen step keeps the growth under 1 %.
TEST_CASE("fixed and adaptive steps agree to 1e-6 on a 5-revolution pulse-train history", "[transient][slow]") {
  const Scene s = paper_scene({"model.terms=8"});  // endless half-sine train, F̄ = 5
  const BladeModel m = assemble_model(s);
  TransientOptions adaptive, fixed, paper;
  adaptive.revolutions = fixed.revolutions = paper.revolutions = 5;
  adaptive.tolerance = 1e-9;
  fixed.adaptive = paper.adaptive = false;
  paper.steps_per_period = 8;
  const TransientResult a = run_transient(m, s, adaptive), f = run_transient(m, s, fixed), p = run_transient(m, s, paper);
  REQUIRE(a.samples.size() == f.samples.size());
  const auto difference = [&](const TransientResult& r, double TransientSample::*field) {
    double peak = 0, d = 0;
    for (std::size_t k = 0; k < a.samples.size(); ++k) {
      peak = std::max(peak, std::abs(a.samples[k].*field));
      d = std::max(d, std::abs(a.samples[k].*field - r.samples[k].*field));
    }
    return d / peak;
  };
  INFO("adaptive " << a.steps.accepted << " steps, fixed " << f.steps.accepted << " steps of " << f.fixed.step_s
                   << " s (1/" << f.fixed.steps_per_period << " period)");
  CHECK(f.fixed.parasitic_growth < 1.01);
  CHECK(difference(f, &TransientSample::tip_lateral_m) < 1e-6);  // measured 1.8e-8
  CHECK(difference(f, &TransientSample::tip_axial_m) < 1e-6);    // measured 4.7e-7
  // The paper's literal step: its predicted growth shows in the history.
  CHECK(p.fixed.steps_per_period == 8);
  CHECK(p.fixed.parasitic_growth > 1e3);
  CHECK(difference(p, &TransientSample::tip_lateral_m) > 1e-4);
}

TEST_CASE("RKF45's stability function: fifth order, and the growth a fixed step really gives", "[transient][rkf45]") {
  // R(z) − e^z = O(z⁶): the error constant is the same at two step sizes.
  const auto c6 = [](double y) { return std::abs(rkf45_stability_function({0, y}) - std::exp(std::complex<double>(0, y))) / std::pow(y, 6); };
  CHECK(c6(0.05) == Approx(c6(0.1)).epsilon(0.01));
  // An undamped oscillator ẍ = −ω²x stepped at ωh = π/4 grows by |R(iπ/4)| per step.
  const double omega = 2.0, h = 3.14159265358979323846 / 4 / omega;
  const int steps = 20000;
  const OdeFunction oscillator = [&](double, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    dx.resize(2);
    dx << omega * x(1), -omega * x(0);
  };
  Eigen::VectorXd x(2);
  x << 1, 0;
  StepControl fixed;
  fixed.adaptive = false;
  fixed.fixed_step = h;
  rkf45_integrate(oscillator, x, 0, steps * h, fixed, {}, {}, [](double, const Eigen::VectorXd&) {});
  const double predicted = std::pow(std::abs(rkf45_stability_function({0, omega * h})), steps);
  CHECK(predicted > 10);  // 1.7e-4 per step
  CHECK(x.norm() == Approx(predicted).epsilon(1e-9));
}

TEST_CASE("crosscheck: the cosine approximation's instability is real for its load, absent for the true pulse", "[transient][crosscheck][slow]") {
  const Scene s = paper_scene({"model.terms=8"});  // half-sine, t̄c = 0.01, one pulse per revolution
  CrosscheckOptions o;
  o.fmax_over_fcr = {5};
  o.revolutions = 16;
  const CrosscheckPoint p = crosscheck(s, o).at(0);
  CHECK(p.floquet_cosine == Approx(2.1992274).epsilon(1e-6));
  CHECK(p.transient_cosine_growth == Approx(p.floquet_cosine).epsilon(1e-3));  // measured 5e-5
  CHECK(std::abs(p.floquet_pulse - 1) < 1e-6);                                  // the real pulse: stable
  CHECK(p.transient_pulse_growth < 1.01);
  CHECK(p.pulse_harmonics == 400);
  CHECK(std::abs(p.rkf45_max_abs_multiplier - 2.1992274) < 1e-6);  // the integrator's own monodromy
  CHECK(p.monodromy_difference < 1e-4);  // against the Magnus one, entry by entry (measured 1.3e-5)
}

TEST_CASE("the follower correction adds the lateral load -F sin(psi) and keeps the axial one F cos(psi)", "[transient]") {
  // Coriolis off and no friction: only the follower's lateral term and the cos ψ factor differ.
  const Scene s = paper_scene({"model.terms=6", "model.coriolis=false", "load.pulse_count=1"});
  const BladeModel m = assemble_model(s);
  TransientOptions plain, follower;
  plain.revolutions = follower.revolutions = 1;
  plain.initial_state = follower.initial_state = perturbed_equilibrium(m, 300, 1e-3, 0);  // ψ ≈ 1.4e-3
  follower.follower = true;
  const TransientResult a = run_transient(m, s, plain), b = run_transient(m, s, follower);
  double peak = 0, diff = 0;
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    peak = std::max(peak, std::abs(a.samples[k].tip_lateral_m));
    diff = std::max(diff, std::abs(a.samples[k].tip_lateral_m - b.samples[k].tip_lateral_m));
  }
  // The lateral impulse F sin ψ · (2/π) t_c ≈ 323 kN · 1.4e-3 · 0.133 ms = 0.06 N s on mode 1
  // (modal mass ≈ 2.5 kg at the tip) changes its velocity by ≈ 0.024 m/s, its amplitude by
  // ≈ 0.024/ω1 = 6e-5 m (measured 8.2e-5 m). Asserted within a factor of about 3 either way.
  CHECK(diff > 2e-5);
  CHECK(diff < 2e-4);
  CHECK(peak == Approx(1e-3).epsilon(0.1));
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    CHECK(a.samples[k].axial_force_n == b.samples[k].axial_force_n);  // the prescribed pulse itself
  }
}

TEST_CASE("clearance mode: a slow casing distortion pushes the tip with the static force of the wall and blade in series", "[transient][clearance][slow]") {
  // δ = 0: the wall touches the running tip and moves in smoothly, d·(1 − cos 2πt/T)/2 over each
  // revolution (47.7 Hz against the 1280 Hz axial mode: quasi-static). At its deepest the tip sits
  // where K(Ω) holds it against F, so F = −d/(1/k + 1/k_tip), k_tip = 1/(p_uᵀK(Ω)⁻¹p_u).
  const double d = 1e-4;
  const BladeModel m = assemble_model(paper_scene({"model.terms=8"}));
  const Eigen::VectorXd p_u = m.tip_axial.transpose();
  const double k_tip = 1 / p_u.dot(m.stiffness(300).ldlt().solve(p_u));
  for (double ratio : {100.0, 1000.0}) {
    const Scene s = paper_scene({"model.terms=8", "load.mode=clearance", "load.clearance=0", "load.intrusion=1e-4",
                                 "load.profile=cosine", "load.contact_time_rev=1",
                                 "load.contact_stiffness=" + std::to_string(ratio * k_tip)});
    TransientOptions o;
    o.revolutions = 1;
    o.tolerance = 1e-9;
    o.samples_per_revolution = 400;
    const TransientResult r = run_transient(m, s, o);
    const double expected = d / (1 / (ratio * k_tip) + 1 / k_tip);
    const TransientSample& deepest = r.samples.at(200);  // half a revolution
    INFO("k = " << ratio << " k_tip, k_tip = " << k_tip << " N/m");
    CHECK(-deepest.axial_force_n == Approx(expected).epsilon(3e-3));  // measured 3e-4 … 6e-4
    CHECK(r.contact->peak_force_n == Approx(expected).epsilon(3e-3));
    CHECK(r.contact->max_overlap_m == Approx(expected / (ratio * k_tip)).epsilon(3e-3));
    CHECK(deepest.tip_axial_m - r.static_tip_axial_m == Approx(-d + expected / (ratio * k_tip)).epsilon(3e-3));
  }
}

TEST_CASE("clearance mode: bouncing on a still casing conserves the energy with the penalty's potential", "[transient][clearance]") {
  // No distortion, 0.05 mm clearance, a 0.1 mm first-axial-mode vibration started on its inward
  // swing: the tip hits the wall every cycle. Undamped, μ = 0: ½ḟᵀMḟ + ½fᵀKf − Ω²P_cfᵀf + ½k g₊² is conserved.
  const Scene s = paper_scene({"model.terms=8", "load.mode=clearance", "load.clearance=5e-5", "load.intrusion=0"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 1;
  o.tolerance = 1e-10;
  o.initial_state = perturbed_equilibrium(m, 300, 0, -1e-4);
  const TransientResult r = run_transient(m, s, o);
  const auto [drift, swing] = energy_drift(r);
  INFO("contacts " << r.contact->closures << ", kinetic energy up to " << swing << " J, drift " << drift << " J");
  CHECK(r.contact->closures >= 20);  // about once per 0.78 ms axial period over 21 ms
  CHECK(r.samples.front().casing_overlap_m < 0);
  CHECK(drift < 1e-8 * swing);  // measured 1.4e-9
}

TEST_CASE("clearance mode: contacts and contact time from the events match a densely sampled overlap", "[transient][clearance]") {
  // The paper blade meeting a 3.5 mm, 3.6° half-sine distortion with 3 mm clearance: a violent rub
  // that opens and closes many times.
  const Scene s = paper_scene({"model.terms=8", "load.mode=clearance", "load.intrusion=3.5e-3"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 3;
  o.samples_per_revolution = 50000;
  const TransientResult r = run_transient(m, s, o);
  int rises = 0, in_contact = 0;
  double peak = 0;
  for (std::size_t k = 1; k < r.samples.size(); ++k) {
    rises += r.samples[k - 1].casing_overlap_m <= 0 && r.samples[k].casing_overlap_m > 0;
    in_contact += r.samples[k].casing_overlap_m > 0;
    peak = std::max(peak, -r.samples[k].axial_force_n);
  }
  const double dt = r.samples[1].time_s - r.samples[0].time_s;
  INFO("contacts " << r.contact->closures << ", contact time " << r.contact->contact_time_s << " s");
  CHECK(r.contact->closures > 20);
  CHECK(r.contact->closures == rises);
  CHECK(std::abs(r.contact->contact_time_s - in_contact * dt) < r.contact->closures * dt);
  CHECK(r.contact->peak_force_n >= peak);               // the event finds the true maximum …
  CHECK(r.contact->peak_force_n < peak * (1 + 1e-2));   // … which the samples come close to
}

TEST_CASE("a fractional number of revolutions is sampled evenly to its end, and its spectrum finds mode 1", "[transient]") {
  // 10.5 revolutions at 64 samples each: 673 samples, one spacing throughout (a shorter last
  // interval would put a kink into the FFT's time base and smear its peaks).
  const Scene s = paper_scene({"model.terms=8", "load.fmax_over_fcr=0"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 10.5;
  o.samples_per_revolution = 64;
  o.initial_state = perturbed_equilibrium(m, 300, 1e-3, 0);
  const TransientResult r = run_transient(m, s, o);
  REQUIRE(r.samples.size() == 10 * 64 + 32 + 1);
  const double dt = two_pi / 300 / 64;
  double worst = 0;
  for (std::size_t k = 1; k < r.samples.size(); ++k) {
    worst = std::max(worst, std::abs(r.samples[k].time_s - r.samples[k - 1].time_s - dt));
  }
  CHECK(worst < 1e-9 * dt);
  CHECK(r.samples.back().revolutions == Approx(10.5).epsilon(1e-12));
  std::vector<double> tip;
  for (const TransientSample& x : r.samples) tip.push_back(x.tip_lateral_m);
  const double f1 = solve_modes(m, system_at(m, 300, Eigen::MatrixXd::Zero(m.layout.size(), m.layout.size())), 300, 1,
                                EigenSolverKind::dense)
                        .modes.at(0)
                        .frequency_hz;
  // The run holds 14 periods of mode 1; the peak, refined by its parabola, within 1 % of it.
  CHECK(dominant_frequency(amplitude_spectrum(tip, 1 / dt)) == Approx(f1).epsilon(0.01));
}
