// The exact pulse-train monodromy (load.approximation = "exact"): against a high-order
// Runge–Kutta integration of the same true pulse train (Boost.Odeint, Fehlberg 7(8)), the closed
// form of the one-dof Meissner equation, the Fourier series as its harmonics grow, and the
// impulse as the limit of ever shorter rectangles.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <unsupported/Eigen/MatrixFunctions>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/ltp/pulse_monodromy.hpp"
#include "reference/odeint_monodromy.hpp"
#include "reference/pulse_profiles.hpp"
#include "support/scenes.hpp"

using namespace bladestab;

namespace {

constexpr double pi = 3.14159265358979323846;

struct Setup {
  Scene scene;
  BladeModel model;
  PeriodicSystem system;
  PulseTrain train;
};

// The paper blade (Legendre, Timoshenko, axial, Coriolis) with `terms` per field, exact load.
Setup setup(const Scene& s) {
  BladeModel m = assemble_model(s);
  PeriodicSystem sys = periodic_system(m, s, load_series(s));
  return {s, std::move(m), std::move(sys), pulse_train(s)};
}

// A small, mildly stiff model for the whole-period references: bending only, six terms.
const std::vector<std::string> small_model{"model.theory=euler-bernoulli", "model.axial=false", "model.terms=6"};

Scene exact_scene(std::vector<std::string> more) {
  more.insert(more.begin(), "load.approximation=exact");
  return testing_support::paper_scene(more);
}

// Φ over [0, t1] for ẏ = A(t) y, A(t) = A₀ + (F(t) − F₀) B (docs/theory.md §4) with the true F(t) of the SPEC's
// table, by Boost.Odeint's controlled Fehlberg 7(8) stepper on each smooth piece
// (tests/reference/odeint_monodromy.hpp): each pulse's two halves (the triangle's kink at t_c/2; F
// and F' jump at the edges) and the free flight after it.
Eigen::MatrixXd odeint_propagator(const PeriodicSystem& sys, const PulseTrain& train, double t1, double tol) {
  const reference::PulseTrainReference pulses{train.profile, train.peak_n, train.contact_time_s, train.period_s, 0};
  std::vector<double> pieces = pulses.edges(t1);
  for (double t0 = 0; t0 < t1; t0 += train.period_s) pieces.push_back(t0 + train.contact_time_s / 2);
  const double F0 = sys.coefficients[0].real();
  return reference::odeint_propagator(sys.A0, sys.B, [&](double t) { return pulses.force(t) - F0; }, pieces, t1, tol);
}

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// Transfer matrix over time t of η̈ = −w2 η in (η, η̇): cos/sin for w2 > 0, cosh/sinh for w2 < 0.
Eigen::Matrix2d oscillator_transfer(double w2, double t) {
  const double w = std::sqrt(std::abs(w2));
  Eigen::Matrix2d R;
  if (w2 > 0) {
    R << std::cos(w * t), std::sin(w * t) / w, -w * std::sin(w * t), std::cos(w * t);
  } else {
    R << std::cosh(w * t), std::sinh(w * t) / w, w * std::sinh(w * t), std::cosh(w * t);
  }
  return R;
}

}  // namespace

TEST_CASE("load.approximation = \"exact\" is accepted, and its series is the pulse's mean alone", "[exact]") {
  const Scene s = exact_scene({"load.contact_time_rev=0.02"});
  CHECK(s.load.approximation == LoadApproximation::exact);
  const LoadSeries series = load_series(s);
  const PulseTrain train = pulse_train(s);
  REQUIRE(series.exact_pulse);
  REQUIRE(series.harmonics() == 0);
  // Half-sine mean: −F_max (2/π) t_c / T_p.
  CHECK(series.coefficients[0].real() ==
        Approx(-train.peak_n * 2 / pi * train.contact_time_s / train.period_s).epsilon(1e-13));
  // The impulse has a mean (−F_max t_c / T_p) though no Fourier series.
  const LoadSeries impulse = load_series(exact_scene({"load.profile=impulse"}));
  CHECK(impulse.coefficients[0].real() ==
        Approx(-train.peak_n * 0.01 * 2 * pi / 300 / train.period_s).epsilon(1e-13));
  try {
    testing_support::paper_scene({"load.approximation=exactly"});
    FAIL("a bad load.approximation was accepted");
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const char* word : {"load.approximation", "exactly", "\"cosine\"", "\"exact\"", "\"fourier\""}) {
      INFO(what);
      CHECK(what.find(word) != std::string::npos);
    }
  }
}

TEST_CASE("multiplier_set_distance matches the sets closest pair first", "[exact]") {
  using c = std::complex<double>;
  Eigen::VectorXcd a(4), b(4);
  a << c(1, 0), c(0, 1), c(-1, 0), c(3, 0);
  b << c(3.03, 0), c(-1.001, 0), c(1, 0), c(0, 1.002);
  // Pairs: 1↔1 (0), i↔1.002i (0.002), −1↔−1.001 (0.001), 3↔3.03 (0.03).
  CHECK(multiplier_set_distance(a, b) == Approx(0.03).epsilon(1e-12));
  // A double root in one set against two distinct roots: each must be used once.
  a << c(1, 0), c(1, 0), c(2, 0), c(0, 0);
  b << c(1, 0), c(0.5, 0), c(2, 0), c(0, 0);
  CHECK(multiplier_set_distance(a, b) == Approx(0.5).epsilon(1e-12));
}

TEST_CASE("Meissner: one dof under rectangular pulses is a product of two closed-form transfers", "[exact]") {
  // One sine mode of the Euler–Bernoulli blade at rest: η̈ + ω0² (1 + F/F_cr) η = 0, so
  // ω² = ω0² (1 − F̄) during contact and ω0² between (the sine mode's Euler load is F_cr exactly).
  for (double fbar : {0.5, 5.0}) {
    for (double tc : {0.05, 0.4}) {
      const Setup s = setup(testing_support::paper_scene(
          {"model.theory=euler-bernoulli", "model.terms=1", "model.axial=false", "model.basis=sine",
           "operation.speed_rad_s=0", "load.approximation=exact", "load.profile=rectangular",
           "load.pulse_frequency_hz=7", "load.fmax_over_fcr=" + std::to_string(fbar),
           "load.contact_time_rev=" + std::to_string(tc)}));
      const double w0 = s.system.modal->frequencies()(0), T = 1.0 / 7, c = tc * T;
      const Eigen::Matrix2d eta = oscillator_transfer(w0 * w0, T - c) * oscillator_transfer(w0 * w0 * (1 - fbar), c);
      const Eigen::Matrix2d S = Eigen::Vector2d(w0, 1).asDiagonal();  // y = [ω0 η; η̇]
      const Eigen::Matrix2d reference = S * eta * S.inverse();
      const PulseMonodromy r = exact_pulse_monodromy(s.system, periodic_pulse(s.train), 1e-12);
      INFO("F̄ = " << fbar << ", t_c/T = " << tc);
      CHECK(relative_difference(r.monodromy, reference) < 1e-10);
      // det Φ = 1 (Liouville), to the rounding of a 2×2 determinant with entries of size ‖Φ‖
      // (a few units of 1e-16 ‖Φ‖², with or without fused multiply–add).
      CHECK(liouville_error(r.monodromy, s.system) < 1e-14 * std::max(1.0, r.monodromy.squaredNorm()));
    }
  }
}

TEST_CASE("every profile: the exact monodromy matches Runge-Kutta 7(8) on the true pulse train", "[exact][long_under_sanitizers]") {
  for (const char* profile : {"half-sine", "cosine", "triangular", "saw-tooth", "rectangular"}) {
    for (const double zeta : {0.0, 0.001}) {  // light damping keeps det Φ = e^{−tr Ĉ T} representable
      std::vector<std::string> o = small_model;
      o.insert(o.end(), {std::string("load.profile=") + profile, "load.contact_time_rev=0.05"});
      if (zeta > 0) o.insert(o.end(), {"damping.model=modal", "damping.ratio=" + std::to_string(zeta)});
      const Setup s = setup(exact_scene(o));
      const PulseMonodromy r = exact_pulse_monodromy(s.system, periodic_pulse(s.train), 1e-10);
      const Eigen::MatrixXd reference = odeint_propagator(s.system, s.train, s.train.period_s, 1e-12);
      const Eigen::VectorXcd rho = Eigen::EigenSolver<Eigen::MatrixXd>(reference, false).eigenvalues();
      INFO(profile << ", ζ = " << zeta << ": " << r.steps << " steps, estimate " << r.error_estimate);
      CHECK(multiplier_set_distance(r.multipliers, rho) < 1e-8);
      // The matrix converges behind its eigenvalues (the stiff modes' phases).
      CHECK(relative_difference(r.monodromy, reference) < 1e-7);
      CHECK(r.error_estimate <= 1e-10);
      CHECK(liouville_error(r.monodromy, s.system) < 1e-10);  // Liouville
    }
  }
}

TEST_CASE("the paper blade at N = 8, t_c = 0.01 rev: the stiff contact against Runge-Kutta 7(8)", "[exact]") {
  // ω_max t_c ≈ 84 at 300 rad/s (the axial and shear modes). 300 rad/s is stable for the true
  // half-sine at F̄ = 5, 118 rad/s lies in one of its narrow tongues.
  for (const double speed : {300.0, 118.0}) {
    const Setup s = setup(exact_scene({"model.terms=8", "operation.speed_rad_s=" + std::to_string(speed)}));
    const PulseMonodromy r = exact_pulse_monodromy(s.system, periodic_pulse(s.train), 1e-9);
    // The reference integrates the contact only; the free flight is a plain matrix exponential.
    const double c = s.train.contact_time_s, T = s.train.period_s;
    const Eigen::MatrixXd A_free = s.system.A0 - s.system.coefficients[0].real() * s.system.B;
    const Eigen::MatrixXd reference = (A_free * (T - c)).exp() * odeint_propagator(s.system, s.train, c, 1e-12);
    const Eigen::VectorXcd rho = Eigen::EigenSolver<Eigen::MatrixXd>(reference, false).eigenvalues();
    INFO("Ω = " << speed << ": " << r.steps << " steps, estimate " << r.error_estimate << ", max|ρ| " << std::abs(r.multipliers(0)));
    CHECK(r.error_estimate <= 1e-9);
    CHECK(multiplier_set_distance(r.multipliers, rho) < 1e-8);
    CHECK(relative_difference(r.monodromy, reference) < 1e-6);
    CHECK(liouville_error(r.monodromy, s.system) < 1e-10);
    CHECK((std::abs(r.multipliers(0)) > 1 + 1e-3) == (speed == 118.0));
  }
}

TEST_CASE("the true train's independent check integrates the contact and takes the flight by eigenvectors",
          "[exact]") {
  // RKF45 through the contact only (1 % of the period), the free flight by e^{Λτ} on the unloaded
  // blade's eigenvectors: the dominant Floquet vector comes back to ρ v within RKF45's accuracy
  // (rtol 1e-9 at this tolerance), and the check runs on the whole N = 16 model too, where an
  // RKF45 integration of the whole period (64 kHz modes) was unaffordable and the residual was n/a.
  // A flight over the wrong time or with the wrong matrix would leave a residual of order one.
  for (const auto& [terms, speed] : {std::pair{8, 118.0}, std::pair{16, 300.0}}) {
    const Setup s = setup(exact_scene({"model.terms=" + std::to_string(terms), "operation.speed_rad_s=" + std::to_string(speed)}));
    const FloquetResult r = pulse_train_multipliers(s.system, periodic_pulse(s.train), {FloquetMethod::monodromy, 0, 1e-8, true});
    INFO("N = " << terms << ", Ω = " << speed << ": max|ρ| " << r.max_abs_multiplier << ", residual " << r.checks.residual);
    CHECK(std::isfinite(r.checks.residual));
    CHECK(r.checks.residual < 1e-7);
  }
}

TEST_CASE("two pulses per revolution: multipliers per pulse period, Φ(T_p)² over a revolution", "[exact]") {
  std::vector<std::string> o = small_model;
  o.insert(o.end(), {"load.pulses_per_rev=2", "load.contact_time_rev=0.03"});
  const Setup s = setup(exact_scene(o));
  const double revolution = 2 * pi / 300;
  CHECK(s.train.period_s == Approx(revolution / 2).epsilon(1e-14));
  CHECK(s.system.period() == Approx(revolution / 2).epsilon(1e-14));
  const PulseMonodromy r = exact_pulse_monodromy(s.system, periodic_pulse(s.train), 1e-10);
  const Eigen::MatrixXd reference = odeint_propagator(s.system, s.train, revolution, 1e-12);
  CHECK(relative_difference(r.monodromy * r.monodromy, reference) < 1e-7);
  const Eigen::VectorXcd per_revolution = Eigen::EigenSolver<Eigen::MatrixXd>(reference, false).eigenvalues();
  CHECK(multiplier_set_distance(r.multipliers.array().square(), per_revolution) < 1e-8);
}

TEST_CASE("the impulse is the limit of ever shorter rectangles of the same impulse, error ∝ t_c", "[exact]") {
  const Setup s = setup(exact_scene({"model.terms=4", "load.profile=impulse", "load.contact_time_rev=0.01"}));
  const PulseMonodromy jump = exact_pulse_monodromy(s.system, periodic_pulse(s.train), 1e-12);
  CHECK(jump.steps == 0);
  CHECK(liouville_error(jump.monodromy, s.system) < 1e-12);
  const double J = s.train.peak_n * s.train.contact_time_s;
  std::vector<double> errors;
  // The asymptotic rate needs ω_max t_c ≪ 1 (ω_max = 3e5 rad/s here): t_c/T from 1e-4.
  for (double tc : {1e-4, 1e-5, 1e-6, 1e-7}) {
    PulseTrain rectangle = s.train;
    rectangle.profile = PulseProfile::rectangular;
    rectangle.contact_time_s = tc * s.train.period_s;
    rectangle.peak_n = J / rectangle.contact_time_s;
    errors.push_back(relative_difference(exact_pulse_monodromy(s.system, periodic_pulse(rectangle), 1e-13).monodromy, jump.monodromy));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    INFO("t_c/T = 1e-" << k + 3 << ": " << errors[k - 1] << " → " << errors[k]);
    CHECK(errors[k - 1] / errors[k] == Approx(10).epsilon(0.1));  // first order in t_c
  }
}

TEST_CASE("the Fourier series' monodromy converges to the exact one as the harmonics grow", "[exact]") {
  // Four bending terms: ω_max = 1.5e4 rad/s, so harmonics beyond ω_max/θ ≈ 50 no longer meet a mode.
  const Setup s = setup(exact_scene({"model.theory=euler-bernoulli", "model.axial=false", "model.terms=4",
                                     "load.contact_time_rev=0.1"}));
  const PulseMonodromy exact = exact_pulse_monodromy(s.system, periodic_pulse(s.train), 1e-12);
  std::vector<double> errors;
  for (int M : {10, 20, 40, 80, 160}) {
    const PeriodicSystem series = periodic_system(s.model, s.scene, fourier_series(s.train, 0, M));
    // Magnus steps doubled until the series' own monodromy is settled far below its truncation error.
    Eigen::MatrixXd previous = magnus_monodromy(series, 16 * M), current = magnus_monodromy(series, 32 * M);
    for (int steps = 64 * M; relative_difference(current, previous) > 1e-11; steps *= 2) {
      previous = current;
      current = magnus_monodromy(series, steps);
    }
    errors.push_back(relative_difference(current, exact.monodromy));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    INFO("M doubled: " << errors[k - 1] << " → " << errors[k]);
    CHECK(errors[k] < errors[k - 1]);
  }
  CHECK(errors.back() < 1e-4);
}
