// Time domain: energy conservation, agreement with the Floquet multipliers, the paper's Fig. 10/11
// single-pulse response, fixed against adaptive steps.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "bladestab/base/constants.hpp"
#include "bladestab/transient/crosscheck.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/ltp/pulse_monodromy.hpp"
#include "bladestab/transient/response_analysis.hpp"
#include "bladestab/transient/transient.hpp"
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

// The growth per revolution under the cosine load against Floquet: test_transient_honesty.cpp (the
// fit, 2e-4) and the crosscheck test below (1e-3).

TEST_CASE("the paper's Fig. 10/11 single pulse: 0.1 mm lateral at mode 1, 0.8 mm axial about 2 mm at the first axial mode", "[transient][paper]") {
  // Sinha §4.2: one half-sine pulse, F̄ = 5, t̄c = 0.01, μ = 0, 300 rad/s, undamped. What the text
  // quotes from its figures, and how it is asserted:
  //  Fig. 10  lateral tip deflection "±0.1 mm" for 60 revolutions, neither growing nor decaying: every
  //           revolution's peak within ±20 % of 0.1 mm (a value read off a plot's axis), over 20;
  //           at "67.0 Hz", the first flexural mode (docs/theory.md §7: 68.035 Hz): within 2 % of the figure's,
  //           0.3 % of the SPEC's (the spectrum's resolution after refinement);
  //           the lateral motion is "the result of the coupling of axial motion with the lateral
  //           motion caused by the Coriolis effect": none without it.
  //  Fig. 11a the tip oscillates about the 2 mm steady stretch (docs/theory.md §7: 2.0 mm; 2 %), "initial
  //           peak-amplitude in the range 1.2 mm ≤ u ≤ 2.8 mm", i.e. 0.8 mm: the first revolution's
  //           half range within 10 % (ours is 7 % above: the paper's RKF45 damps, and by its own
  //           account its later "settling down to 1.8–2.2 mm" is numerical damping, not asserted).
  //           Independently of the figure, the first axial mode's share of the response is the
  //           closed-form single-pulse response of that mode (1.0 mm; within 0.3 %, below).
  //  Fig. 11b "the beam responds at 1286 Hz": the first axial mode (docs/theory.md §8), of the spinning bar
  //           ω² = (π/2L)² E/ρ − Ω² (docs/theory.md §1): within 0.3 % of it, 1 % of the figure's.
  //  Fig. 11c no spurious build-up of strain energy: every revolution's peak strain energy within
  //           1 % of the first's, and the total energy after the pulse constant.
  const Scene s = paper_scene({"model.terms=8", "load.pulse_count=1"});  // half-sine, F̄ = 5, t̄c = 0.01, μ = 0
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 20;
  o.tolerance = 1e-7;
  const TransientResult r = run_transient(m, s, o);
  const double L = 1.0, E = 117e9, rho = 4466.0, A = 22.39e-4, W = 300;
  const PulseTrain train = pulse_train(s);

  // Fig. 10.
  std::vector<double> lateral_peak(20, 0), strain_peak(20, 0), axial_low(20, 1), axial_high(20, 0);
  std::vector<double> lat, ax, time;
  double energy_low = 1e300, energy_high = -1e300;
  for (const TransientSample& p : r.samples) {
    const int rev = std::min(19, static_cast<int>(p.revolutions));
    lateral_peak[rev] = std::max(lateral_peak[rev], std::abs(p.tip_lateral_m));
    strain_peak[rev] = std::max(strain_peak[rev], p.strain_energy_j);
    axial_low[rev] = std::min(axial_low[rev], p.tip_axial_m);
    axial_high[rev] = std::max(axial_high[rev], p.tip_axial_m);
    lat.push_back(p.tip_lateral_m), ax.push_back(p.tip_axial_m), time.push_back(p.time_s);
    if (p.time_s > train.contact_time_s) {
      energy_low = std::min(energy_low, p.total_energy_j), energy_high = std::max(energy_high, p.total_energy_j);
    }
  }
  for (int rev = 0; rev < 20; ++rev) {
    INFO("revolution " << rev + 1 << ": lateral peak " << lateral_peak[rev] << " m, strain energy peak "
                       << strain_peak[rev] << " J");
    CHECK(lateral_peak[rev] == Approx(1e-4).epsilon(0.2));  // measured 0.090 to 0.103 mm
    CHECK(strain_peak[rev] == Approx(strain_peak[0]).epsilon(0.01));  // measured 0.1 %
  }
  const double rate = 200 * W / two_pi;
  const double f_lateral = dominant_frequency(amplitude_spectrum(lat, rate)).value();
  CHECK(f_lateral == Approx(67.0).epsilon(0.02));      // measured 68.033 Hz
  CHECK(f_lateral == Approx(68.035).epsilon(0.003));
  // Without Coriolis coupling the pulse leaves the lateral tip alone.
  {
    const Scene uncoupled = paper_scene({"model.terms=8", "load.pulse_count=1", "model.coriolis=false"});
    TransientOptions one = o;
    one.revolutions = 1;
    double largest = 0;
    for (const TransientSample& p : run_transient(assemble_model(uncoupled), uncoupled, one).samples) {
      largest = std::max(largest, std::abs(p.tip_lateral_m));
    }
    CHECK(largest < 1e-12);  // against 1e-4 m with it
  }

  // Fig. 11a, b.
  double mean = 0;
  for (double a : ax) mean += a / ax.size();
  CHECK(mean == Approx(2.0e-3).epsilon(0.02));
  CHECK((axial_high[0] - axial_low[0]) / 2 == Approx(0.8e-3).epsilon(0.1));  // measured 0.857 mm
  const double omega_axial = std::sqrt(std::pow(pi / (2 * L), 2) * E / rho - W * W);
  const double f_axial = dominant_frequency(amplitude_spectrum(ax, rate), 600).value();
  CHECK(f_axial == Approx(omega_axial / two_pi).epsilon(0.003));  // measured 1279.63 Hz, the bar 1278.71
  CHECK(f_axial == Approx(1286).epsilon(0.01));
  // The first axial mode φ = sin(πs/2L) (modal mass ρAL/2, φ(L) = 1) after the pulse:
  // q(t) = Im[e^{iωt} F̂(ω)]/(m ω), F̂(ω) = ∫F e^{−iωτ}dτ = −F_max a(1 + e^{−iωt_c})/(a² − ω²), a = π/t_c.
  // Its amplitude against the run's component at the model's own first axial frequency (with
  // Coriolis 0.07 % above the bar's), projected over the 20 revolutions (537 of its periods).
  const ModalSolution modes = solve_modes(m, system_at(m, W, damping_matrix(m, s.damping, W)), W, 6, EigenSolverKind::dense);
  double omega = 0;
  for (const Mode& mode : modes.modes) if (mode.family == ModeFamily::axial && omega == 0) omega = two_pi * mode.frequency_hz;
  const double a = pi / train.contact_time_s;
  const std::complex<double> pulse_transform =
      -train.peak_n * a * (1.0 + std::exp(std::complex<double>(0, -omega * train.contact_time_s))) / (a * a - omega * omega);
  const double closed_form = std::abs(pulse_transform) / (rho * A * L / 2 * omega);
  std::complex<double> projection = 0;
  for (std::size_t k = 0; k < ax.size(); ++k) projection += (ax[k] - mean) * std::exp(std::complex<double>(0, -omega * time[k]));
  const double component = 2 * std::abs(projection) / ax.size();
  INFO("first axial mode: closed form " << closed_form << " m, in the run " << component << " m");
  CHECK(component == Approx(closed_form).epsilon(0.003));  // measured 2.7e-4

  // Fig. 11c.
  // Drift against the energy the pulse put in (213 J): measured 3e-7.
  CHECK(energy_high - energy_low < 1e-5 * (energy_high - r.samples.front().total_energy_j));
  REQUIRE(r.growth.omitted.empty());
  CHECK(r.growth.growth == Approx(1).epsilon(0.01));  // undamped, one pulse: steady
  WARN("Fig. 10/11: lateral " << f_lateral << " Hz, peaks " << *std::min_element(lateral_peak.begin(), lateral_peak.end())
                              << " to " << *std::max_element(lateral_peak.begin(), lateral_peak.end())
                              << " m; axial " << f_axial << " Hz, mean " << mean << " m, first revolution "
                              << axial_low[0] << " to " << axial_high[0] << " m, first mode " << component
                              << " m (closed form " << closed_form << "); energy drift " << energy_high - energy_low
                              << " J");
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
  o.revolutions = 10;
  const CrosscheckPoint p = crosscheck(s, o).at(0);
  CHECK(p.floquet_cosine == Approx(2.1992274).epsilon(1e-6));
  INFO("transient growth " << p.transient_cosine_growth << ", Floquet " << p.floquet_cosine);
  CHECK(p.transient_cosine_growth == Approx(p.floquet_cosine).epsilon(1e-3));  // measured 5e-6 (10 revolutions)
  CHECK(std::abs(p.floquet_pulse - 1) < 1e-6);                                  // the real pulse: stable
  CHECK(p.transient_pulse_growth < 1.01);
  CHECK(std::abs(p.rkf45_max_abs_multiplier - 2.1992274) < 1e-6);  // the integrator's own monodromy
  CHECK(p.monodromy_difference < 1e-4);  // against the Magnus one, entry by entry (measured 1.3e-5)

}

TEST_CASE("load series: the true pulse's 400-harmonic series, its Parseval tail and its multipliers against the train's",
          "[transient][crosscheck][slow]") {
  // Its Parseval tail, from the half-sine's closed-form coefficients F_m = −(F_max/T) a(1 + e^{−i mθ
  // t_c})/(a² − (mθ)²), a = π/t_c (−i t_c/2 in place of the fraction at mθ = a), and ⟨F²⟩ =
  // F_max² t_c/(2T). Asked for 1e-3 within 400 harmonics it gets 1.6e-2 (a half-sine 1 % of the
  // period long needs ~2600).
  const Scene s = paper_scene({"model.terms=8"});
  Scene pulse = s;
  pulse.load.fmax_over_fcr = 5;
  pulse.load.approximation = LoadApproximation::fourier;
  const LoadSeries series_load = load_series(pulse, 1e-3, 400);
  const PulseTrain train = pulse_train(pulse);
  const double T = train.period_s, tc = train.contact_time_s, a = pi / tc, theta = two_pi / T;
  const auto coefficient = [&](int m) {
    const double b = m * theta;
    const std::complex<double> integral =
        std::abs(a - b) < 1e-9 * a ? std::complex<double>(0, -tc / 2)
                                   : a * (1.0 + std::exp(std::complex<double>(0, -b * tc))) / (a * a - b * b);
    return -train.peak_n / T * integral;
  };
  double captured = std::norm(coefficient(0));
  for (int m = 1; m <= series_load.harmonics(); ++m) captured += 2 * std::norm(coefficient(m));
  const double tail = std::sqrt(1 - captured / (train.peak_n * train.peak_n * tc / (2 * T)));
  CHECK(series_load.harmonics() == 400);
  CHECK(series_load.relative_tail == Approx(tail).epsilon(1e-9));
  // Yet the Floquet answer is converged at that truncation: the series against the true pulse
  // (pulse_monodromy.hpp: the contact integrated, no series) on the same reduced system, max|ρ|
  // within 1e-6 of the undamped train's 1 and the whole multiplier set within 1e-6 (measured 1e-8;
  // the harmonics beyond 400, above 19 kHz, average out).
  const BladeModel model = assemble_model(s);
  const PeriodicSystem series_system = periodic_system(model, pulse, series_load);
  const FloquetResult series = floquet_multipliers(series_system, {FloquetMethod::monodromy, 0, 1e-8});
  const PulseMonodromy exact = exact_pulse_monodromy(series_system, periodic_pulse(train), 1e-10);
  const double set_distance = multiplier_set_distance(series.multipliers, exact.multipliers);
  CHECK(std::abs(series.max_abs_multiplier - 1) < 1e-6);
  CHECK(set_distance < 1e-6);
  WARN("true pulse: 400 harmonics, Parseval tail " << series_load.relative_tail << " (closed form " << tail
                                                   << "); multipliers " << set_distance << " from the true pulse's");
}

TEST_CASE("crosscheck: with friction, an unstable point's growing response keeps the friction's direction",
          "[transient][crosscheck]") {
  // F̄ = 10 under the cosine load grows 954 a revolution: within a revolution the tip's lateral
  // velocity passes the rim speed and would reverse the sliding. The crosscheck compares the linear
  // equations the multipliers belong to, whose friction is a fixed multiple of F (theory.md §5.8),
  // and which the friction's forcing leaves alone: the growth must still be the multiplier's.
  const Scene s = paper_scene({"model.terms=8", "load.friction=0.5"});
  CrosscheckOptions o;
  o.fmax_over_fcr = {10};
  o.revolutions = 8;
  const CrosscheckPoint p = crosscheck(s, o).at(0);
  INFO("cosine: Floquet " << p.floquet_cosine << " ± " << p.floquet_cosine_error << ", transient "
                          << p.transient_cosine_growth << " ± " << p.transient_cosine_error);
  CHECK(p.rkf45_max_abs_multiplier == Approx(p.floquet_cosine).epsilon(1e-7));  // independent of the friction
  CHECK(p.transient_cosine_growth == Approx(p.rkf45_max_abs_multiplier).epsilon(1e-5));
  CHECK(p.cosine_agrees());
  CHECK(p.pulse_agrees());
}

TEST_CASE("crosscheck: five pulses a revolution, the true train on the whole model, as stability takes it",
          "[transient][crosscheck]") {
  // The paper blade at 16 terms, F̄ = 5, five half-sine pulses a revolution. Undamped and stable, so
  // every multiplier lies on the unit circle: max|ρ| = 1 and no growth. The automatic reduction of 3
  // vectors per load level opens a tongue there (max|ρ| 1.0169343 per period, its transient growing
  // 1.0876 a revolution once it dominates), which the whole model does not have; the crosscheck's
  // pulse rows run on the whole model, as `stability` does for the true train.
  CrosscheckOptions o;
  o.fmax_over_fcr = {5};
  const CrosscheckPoint p = crosscheck(paper_scene({"load.pulses_per_rev=5"}), o).at(0);
  INFO("pulse: Floquet " << p.floquet_pulse << " ± " << p.floquet_pulse_error << " on " << p.pulse_modes
                         << " modes, transient " << p.transient_pulse_growth << " ± " << p.transient_pulse_error);
  CHECK(p.load_periods_per_revolution == Approx(5).epsilon(1e-12));
  CHECK(p.pulse_modes == 48);
  CHECK(std::abs(p.floquet_pulse - 1) <= p.floquet_pulse_error + 1e-9);
  CHECK(std::abs(p.transient_pulse_growth - 1) <= 1e-5);
  CHECK(p.pulse_agrees());
  CHECK(p.cosine_agrees());
}

TEST_CASE("crosscheck: a heavily damped blade's transient decays at the Floquet max|rho|, not at the rounding's 1",
          "[transient][crosscheck]") {
  // Rayleigh damping ζ = 0.3 at 100 Hz and 1 kHz: max|ρ| ≈ 0.027, so a revolution's change falls by
  // ~37 each revolution and reaches the rounding of the periodic state (then exactly 0) within 12.
  // The growth is fitted on the changes still resolved, and carried on from the last of them.
  const Scene s = paper_scene({"model.terms=6", "damping.model=\"rayleigh\"", "damping.ratio=0.3",
                               "damping.frequencies_hz=[100, 1000]"});
  CrosscheckOptions o;
  o.fmax_over_fcr = {1};
  o.revolutions = 16;
  const CrosscheckPoint p = crosscheck(s, o).at(0);
  INFO("cosine: Floquet " << p.floquet_cosine << ", transient " << p.transient_cosine_growth << " ± "
                          << p.transient_cosine_error << "; pulse: Floquet " << p.floquet_pulse << ", transient "
                          << p.transient_pulse_growth << " ± " << p.transient_pulse_error);
  CHECK(p.floquet_cosine < 0.05);
  CHECK(p.cosine_agrees());
  CHECK(p.pulse_agrees());
  CHECK(p.transient_cosine_growth == Approx(p.floquet_cosine).epsilon(0.1));
  CHECK(p.transient_pulse_growth == Approx(p.floquet_pulse).epsilon(0.1));
}

TEST_CASE("crosscheck: with five pulses a revolution the growth per revolution is the multiplier per load period "
          "to the fifth", "[transient][crosscheck]") {
  // The Floquet multipliers are per load period (a fifth of a revolution here), the transient's
  // growth per revolution: under the cosine load at F̄ = 5, 1.1414716 per period is 1.93787 per revolution,
  // and 16 revolutions' transient gives 1.94134 ± 0.15 (its other multipliers still fading).
  const Scene s = paper_scene({"model.terms=8", "load.pulses_per_rev=5"});
  CrosscheckOptions o;
  o.fmax_over_fcr = {5};
  const CrosscheckPoint p = crosscheck(s, o).at(0);
  CHECK(p.load_periods_per_revolution == Approx(5).epsilon(1e-12));
  CHECK(p.floquet_cosine > 1.1);
  CHECK(p.transient_cosine_growth == Approx(std::pow(p.floquet_cosine, 5)).epsilon(1e-2));
  CHECK(std::abs(p.transient_cosine_growth - p.floquet_cosine) > p.transient_cosine_error);  // per revolution ≠ per period
  CHECK(p.cosine_agrees());
  CHECK(p.pulse_agrees());
}

TEST_CASE("the follower correction applies F cos(psi) along the span and -F sin(psi) laterally", "[transient]") {
  // Coriolis off and no friction; the tip bent 0.2 m in mode 1 (ψ ≈ 0.3 rad, far beyond the
  // blade's real slopes, so that 1 − cos ψ ≈ 4 % shows: the model is linear, only the load law is
  // tested). Reference: the equations of motion with the follower loads of docs/theory.md §5, written here
  // from the model's matrices, M f̈ + K(Ω) f = Ω² P_cf + F_ax (p_u − G f) + F_lat p_v with
  // F_ax = F cos ψ, F_lat = −F sin ψ, ψ = v'(L) = Σ Y_k (the integrated Legendre φ_k' = P_{k−1} is 1
  // at the tip), F the half-sine (38), integrated by Boost.Odeint's Dormand–Prince at rtol 1e-11.
  const Scene s = paper_scene({"model.terms=6", "model.coriolis=false", "load.pulse_count=1"});
  const BladeModel m = assemble_model(s);
  const PulseTrain train = pulse_train(s);
  const int n = m.layout.size();
  TransientOptions follower;
  follower.follower = true;
  follower.revolutions = 0.05;  // the pulse (0.01) and four times as long in free flight
  follower.samples_per_revolution = 2000;
  follower.tolerance = 1e-11;
  follower.initial_state = perturbed_equilibrium(m, 300, 0.2, 0);
  follower.max_lateral_over_length = HUGE_VAL;  // the 0.2 m bend is deliberate
  const TransientResult r = run_transient(m, s, follower);

  enum class Law { follower, axial_without_cos, without_lateral };
  const auto reference = [&](Law law) {
    using State = std::vector<double>;
    const Eigen::LLT<Eigen::MatrixXd> mass(m.M);
    const Eigen::MatrixXd K = m.stiffness(300);
    const Eigen::VectorXd steady = m.steady_load(300), p_u = m.tip_axial.transpose(), p_v = m.tip_lateral.transpose();
    const double peak = 5 * m.blade.critical_load(), contact = train.contact_time_s;
    const auto rhs = [&](const State& y, State& dy, double t) {
      const Eigen::Map<const Eigen::VectorXd> f(y.data(), n), v(y.data() + n, n);
      Eigen::Map<Eigen::VectorXd>(dy.data(), n) = v;
      Eigen::VectorXd force = steady - K * f;
      if (t < contact) {
        const double F = -peak * std::sin(pi * t / contact);  // (38)
        const double psi = f.segment(m.layout.lateral_offset(), m.layout.lateral_count).sum();
        const double axial = law == Law::axial_without_cos ? F : F * std::cos(psi);
        const double lateral = law == Law::without_lateral ? 0 : -F * std::sin(psi);
        force += axial * (p_u - m.G * f) + lateral * p_v;
      }
      Eigen::Map<Eigen::VectorXd>(dy.data() + n, n) = mass.solve(force);
    };
    State x(follower.initial_state->data(), follower.initial_state->data() + 2 * n);
    std::vector<double> times;
    for (const TransientSample& p : r.samples) times.push_back(p.time_s);
    const auto split = std::lower_bound(times.begin(), times.end(), contact);
    std::vector<State> states;
    const auto keep = [&](const State& y, double) { states.push_back(y); };
    auto stepper = boost::numeric::odeint::make_dense_output<boost::numeric::odeint::runge_kutta_dopri5<State>>(
        1e-11 * 1e-3, 1e-11);
    // Through the pulse, then the free flight: F' jumps at t_c.
    boost::numeric::odeint::integrate_times(stepper, rhs, x, times.begin(), split, contact / 100, keep);
    if (*(split - 1) < contact) {
      boost::numeric::odeint::integrate_adaptive(stepper, rhs, x, *(split - 1), contact, contact / 100);
    }
    boost::numeric::odeint::integrate_times(stepper, rhs, x, split, times.end(), contact / 100, keep);
    return states;
  };
  const std::vector<std::vector<double>> exact = reference(Law::follower);
  REQUIRE(exact.size() == r.samples.size());
  const auto tip = [&](const std::vector<double>& y, const Eigen::RowVectorXd& row) {
    return row.dot(Eigen::Map<const Eigen::VectorXd>(y.data(), n));
  };
  // Largest difference of the library's tip history from a reference, relative to the excursion.
  const auto history_difference = [&](const std::vector<std::vector<double>>& states, const Eigen::RowVectorXd& row,
                                      double TransientSample::*field) {
    double excursion = 0, difference = 0;
    for (std::size_t k = 0; k < states.size(); ++k) {
      excursion = std::max(excursion, std::abs(tip(states[k], row) - tip(exact[0], row)));
      difference = std::max(difference, std::abs(r.samples[k].*field - tip(states[k], row)));
    }
    return difference / excursion;
  };
  const double lateral = history_difference(exact, m.tip_lateral, &TransientSample::tip_lateral_m);
  const double axial = history_difference(exact, m.tip_axial, &TransientSample::tip_axial_m);
  CHECK(lateral < 1e-9);  // measured 1.3e-12
  CHECK(axial < 1e-9);    // measured 1.9e-12
  // Either component left out is far outside that (measured 4e-2 and 0.6): the check sees both.
  const double without_cos = history_difference(reference(Law::axial_without_cos), m.tip_axial, &TransientSample::tip_axial_m);
  const double without_sin = history_difference(reference(Law::without_lateral), m.tip_lateral, &TransientSample::tip_lateral_m);
  CHECK(without_cos > 1e-3);
  CHECK(without_sin > 1e-3);

  // The loads the library applied, sample by sample through the pulse, against F cos ψ and −F sin ψ
  // with ψ from the reference's state.
  int in_pulse = 0;
  double worst = 0, largest_psi = 0;
  for (std::size_t k = 0; k < r.samples.size(); ++k) {
    const TransientSample& p = r.samples[k];
    if (p.axial_force_n == 0) continue;
    ++in_pulse;
    const double psi = Eigen::Map<const Eigen::VectorXd>(exact[k].data(), n)
                           .segment(m.layout.lateral_offset(), m.layout.lateral_count)
                           .sum();
    INFO("t = " << p.time_s << " s, F = " << p.axial_force_n << " N, ψ = " << psi);
    // The reference's ψ is the library's to ~1e-12 (the histories above): measured ≤ 2e-9 N.
    CHECK(std::abs(p.applied_axial_n - p.axial_force_n * std::cos(psi)) < 1e-10 * train.peak_n);
    CHECK(std::abs(p.applied_lateral_n + p.axial_force_n * std::sin(psi)) < 1e-10 * train.peak_n);
    worst = std::max({worst, std::abs(p.applied_axial_n - p.axial_force_n * std::cos(psi)),
                      std::abs(p.applied_lateral_n + p.axial_force_n * std::sin(psi))});
    largest_psi = std::max(largest_psi, std::abs(psi));
  }
  CHECK(in_pulse >= 15);
  CHECK(largest_psi > 0.25);
  // Without the correction the load is F along the span and nothing laterally.
  TransientOptions plain = follower;
  plain.follower = false;
  plain.revolutions = 0.01;
  for (const TransientSample& p : run_transient(m, s, plain).samples) {
    CHECK(p.applied_axial_n == p.axial_force_n);
    CHECK(p.applied_lateral_n == 0);
  }
  WARN("follower: history differences " << lateral << " (lateral), " << axial << " (axial); without cos ψ "
                                         << without_cos << ", without the lateral load " << without_sin
                                         << "; applied loads within " << worst << " N at " << in_pulse
                                         << " samples, ψ up to " << largest_psi);
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

TEST_CASE("clearance mode: bouncing on a still casing conserves the energy with the penalty's potential", "[transient][clearance][long_under_sanitizers]") {
  // No distortion, 0.05 mm clearance, a 0.1 mm first-axial-mode vibration started on its inward
  // swing: the tip hits the wall every cycle. Undamped, μ = 0: ½ḟᵀMḟ + ½fᵀKf − Ω²P_cfᵀf + ½k g₊² is conserved.
  const Scene s = paper_scene({"model.terms=8", "load.mode=clearance", "load.clearance=5e-5", "load.intrusion=0"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 1;
  o.tolerance = o.contact_tolerance = 1e-10;
  o.initial_state = perturbed_equilibrium(m, 300, 0, -1e-4);
  const TransientResult r = run_transient(m, s, o);
  const auto [drift, swing] = energy_drift(r);
  INFO("contacts " << r.contact->closures << ", kinetic energy up to " << swing << " J, drift " << drift << " J");
  CHECK(r.contact->closures >= 20);  // about once per 0.78 ms axial period over 21 ms
  CHECK(r.samples.front().casing_overlap_m < 0);
  CHECK(drift < 1e-8 * swing);  // measured 1.4e-9
}

TEST_CASE("clearance mode: contacts and contact time from the events match a densely sampled overlap", "[transient][clearance][long_under_sanitizers]") {
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
  CHECK(r.samples.back().revolutions == 10.5);
  CHECK(r.samples[320].revolutions == 5);  // the sample grid, exactly
  std::vector<double> tip;
  for (const TransientSample& x : r.samples) tip.push_back(x.tip_lateral_m);
  const double f1 = solve_modes(m, system_at(m, 300, Eigen::MatrixXd::Zero(m.layout.size(), m.layout.size())), 300, 1,
                                EigenSolverKind::dense)
                        .modes.at(0)
                        .frequency_hz;
  // The run holds 14 periods of mode 1; the peak, refined by its parabola, within 1 % of it.
  CHECK(dominant_frequency(amplitude_spectrum(tip, 1 / dt)).value() == Approx(f1).epsilon(0.01));
}

TEST_CASE("60 revolutions at 300 rad/s end at revolution 60 exactly, by both methods", "[transient]") {
  // t = 60 · 2π/300 carries rounding (t·Ω/2π = 59.99999999999999); the count comes from the
  // sample grid.
  const Scene s = paper_scene({"model.terms=4"});
  const BladeModel m = assemble_model(s);
  for (TransientMethod method : {TransientMethod::fast, TransientMethod::rkf45}) {
    TransientOptions o;
    o.method = method;
    o.revolutions = method == TransientMethod::fast ? 60 : 3;
    o.samples_per_revolution = 7;
    const TransientResult r = run_transient(m, s, o);
    CHECK(r.samples.back().revolutions == o.revolutions);
    for (std::size_t k = 0; k < r.samples.size(); ++k) CHECK(r.samples[k].revolutions == static_cast<double>(k) / 7);
  }
}

TEST_CASE("the amplitude spectrum of a sine sampled a prime number of times: its frequency and amplitude",
          "[transient]") {
  // 4001 samples at 4 kHz of 2.5 sin(2π·123.4 t) + 0.7: between two bins of either grid. The Hann
  // window's scalloping keeps the largest bin within 15 % below the amplitude (1.42 dB).
  constexpr std::size_t n = 4001;
  const double rate = 4000, f0 = 123.4, a = 2.5;
  std::vector<double> signal(n);
  for (std::size_t k = 0; k < n; ++k) signal[k] = a * std::sin(2 * pi * f0 * k / rate) + 0.7;
  const Spectrum s = amplitude_spectrum(signal, rate);
  REQUIRE(s.frequency_hz.size() == s.amplitude.size());
  CHECK(s.frequency_hz.back() == Approx(rate / 2).epsilon(1e-3));
  CHECK(dominant_frequency(s).value() == Approx(f0).epsilon(1e-4));
  const double largest = *std::max_element(s.amplitude.begin(), s.amplitude.end());
  CHECK(largest <= a * 1.001);
  CHECK(largest >= 0.85 * a);
}
