// load.profile = "impulse" in the transient (docs/theory.md §3, (A.5): total impulse J = F_max t_c, duration
// → 0). The transient applies it as a rectangle of height F_max and width t_c; as t_c → 0 its
// response must become the free vibration after the velocity jump Δḟ = −J M⁻¹(p_u − G f), computed
// here from the test's own modal solution of the first-order free system. The impulse as the limit
// of short rectangles in the exact monodromy is in test_pulse_monodromy.cpp; the refusal of its
// Fourier series by `stability` in test_bad_input.cpp, by `boundaries` and `map` here.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/transient/transient.hpp"
#include "reference/first_order_modes.hpp"
#include "support/run_cli.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

// f(t) of the free M f̈ + C ḟ + K f = 0 from f(0), ḟ(0), by the eigen-decomposition A = V Λ V⁻¹ of
// its first-order form in the test's own scaled modal coordinates (reference/first_order_modes.hpp).
struct FreeVibration {
  reference::FirstOrderModes modes;
  Eigen::MatrixXcd V, V_inverse;
  Eigen::VectorXcd lambda;

  FreeVibration(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K) : modes(M, C, K) {
    const Eigen::EigenSolver<Eigen::MatrixXd> eigen(modes.A);
    V = eigen.eigenvectors();
    V_inverse = V.inverse();
    lambda = eigen.eigenvalues();
  }
  Eigen::VectorXd displacement(const Eigen::VectorXd& f0, const Eigen::VectorXd& v0, double t) const {
    const Eigen::VectorXcd y = V * (lambda * t).array().exp().matrix().asDiagonal() * (V_inverse * modes.state(f0, v0));
    return modes.displacement(y.real());
  }
};

}  // namespace

TEST_CASE("impulse in the transient: as t_c -> 0 the response is the free vibration after the jump -J M^-1 (p_u - G f)",
          "[transient][impulse]") {
  // One impulse on the paper blade (four Timoshenko terms per field, Coriolis coupling on), from the
  // rotating equilibrium. The rectangle of width t_c centred at t_c/2 acts on each mode like a jump
  // there up to (ω t_c)²/24: second order in t_c.
  std::vector<double> errors;
  for (const double contact_rev : {1e-4, 1e-5}) {
    const Scene s = paper_scene({"model.terms=4", "load.profile=impulse", "load.pulse_count=1",
                                 "load.contact_time_rev=" + std::to_string(contact_rev)});
    const BladeModel m = assemble_model(s);
    const double speed = s.operation.speed_rad_s, revolution = 2 * 3.14159265358979323846 / speed;
    const double peak = s.load.fmax_over_fcr * m.blade.critical_load(), contact = contact_rev * revolution;
    TransientOptions o;
    o.revolutions = 1;
    o.tolerance = 1e-10;
    const TransientResult r = run_transient(m, s, o);
    const int n = m.layout.size();
    const Eigen::VectorXd equilibrium = rotating_equilibrium(m, speed).head(n);
    // The jump: ∫F dt = −F_max t_c times the tip load's direction p_u − G f at the equilibrium
    // (the geometric term vanishes there: G acts on v, the equilibrium only stretches u).
    const double J = peak * contact;
    const Eigen::VectorXd jump = -J * m.M.llt().solve(Eigen::VectorXd(m.tip_axial.transpose() - m.G * equilibrium));
    const FreeVibration free(m.M, m.gyroscopic(speed), m.stiffness(speed));
    double peak_lateral = 0, peak_axial = 0, d_lateral = 0, d_axial = 0;
    for (const TransientSample& x : r.samples) {
      if (x.time_s < contact) continue;
      const Eigen::VectorXd f = free.displacement(Eigen::VectorXd::Zero(n), jump, x.time_s - contact / 2);
      const double lateral = m.tip_lateral.dot(f), axial = m.tip_axial.dot(f);
      peak_lateral = std::max(peak_lateral, std::abs(lateral));
      peak_axial = std::max(peak_axial, std::abs(axial));
      d_lateral = std::max(d_lateral, std::abs(x.tip_lateral_m - m.tip_lateral.dot(equilibrium) - lateral));
      d_axial = std::max(d_axial, std::abs(x.tip_axial_m - r.static_tip_axial_m - axial));
    }
    INFO("t_c = " << contact_rev << " rev: J = " << J << " N s, peaks " << peak_lateral << " m lateral, " << peak_axial
                  << " m axial; differences " << d_lateral / peak_lateral << ", " << d_axial / peak_axial);
    CHECK(peak_axial > 1e-7);    // the jump moves the tip (about 2.7e-5 J/(N s) m)
    CHECK(peak_lateral > 1e-9);  // and, through the Coriolis coupling, sideways
    errors.push_back(std::max(d_lateral / peak_lateral, d_axial / peak_axial));
  }
  INFO("relative differences " << errors[0] << " (t_c = 1e-4 rev), " << errors[1] << " (1e-5 rev)");
  CHECK(errors[1] < 1e-5);  // measured 5.5e-6: the highest axial modes' (ω t_c)²/24
  // Second order: ×100 per decade of t_c (measured 100.1); a jump placed at t = 0 instead of t_c/2
  // would leave a first-order error (×10).
  CHECK(errors[0] / errors[1] > 50);
  CHECK(errors[0] / errors[1] < 200);
}

TEST_CASE("impulse: boundaries and map refuse its Fourier series with the one-line input error",
          "[impulse][bad_input]") {
  const std::vector<std::string> scene{testing_support::paper_scene_path(), "--set", "model.terms=4",
                                       "--set", "load.profile=impulse", "--set", "load.approximation=fourier"};
  for (std::vector<std::string> args : {std::vector<std::string>{"boundaries"},
                                        std::vector<std::string>{"map", "--plane", "theta-fmax", "--chart", "none"}}) {
    args.insert(args.begin() + 1, scene.begin(), scene.end());
    testing_support::expect_rejected(args, {"load.profile = \"impulse\"", "load.approximation = \"fourier\"",
                                            "no convergent Fourier series"});
  }
}

TEST_CASE("impulse: crosscheck refuses it, a rectangle in the time domain and a jump in the frequency domain",
          "[impulse][bad_input][crosscheck]") {
  // Compared, the two would differ as loads (the paper blade at 16 terms, F̄ = 5: the jump's max|ρ|
  // 1.0735 against the 0.2 ms rectangle's growth 1.0103), not as methods.
  testing_support::expect_rejected({"crosscheck", testing_support::paper_scene_path(), "--set", "load.profile=impulse"},
                                   {"load.profile = \"impulse\"", "jump limit", "load.profile = \"rectangular\""});
}

TEST_CASE("impulse: its velocity jump has no continuum limit, and the analyses refuse it",
          "[impulse][bad_input][exact]") {
  // The jump Δḟ = J M⁻¹ K_g f kicks every Ritz mode alike: the true train's max|ρ| on the whole model
  // does not settle as the terms grow (1.07 at 16, 1.92 at 36), so no number answers for the blade.
  std::vector<double> rho;
  for (const int terms : {16, 36}) {
    Scene s = paper_scene({"model.terms=" + std::to_string(terms), "load.profile=impulse"});
    s.load.approximation = LoadApproximation::exact;
    const BladeModel m = assemble_model(s);
    const PeriodicSystem whole = periodic_system(m, s, exact_pulse_mean(pulse_train(s)), {ReductionKind::none, 0, 0});
    rho.push_back(
        pulse_train_multipliers(whole, periodic_pulse(pulse_train(s)), {FloquetMethod::monodromy, 0, 1e-8})
            .max_abs_multiplier);
  }
  CAPTURE(rho[0], rho[1]);
  CHECK(rho[1] - rho[0] > 0.5);
  const std::vector<std::string> scene{testing_support::paper_scene_path(), "--set", "model.terms=4", "--set",
                                       "load.profile=impulse", "--set", "load.approximation=exact"};
  for (std::vector<std::string> args : {std::vector<std::string>{"stability"}, std::vector<std::string>{"boundaries"},
                                        std::vector<std::string>{"map", "--plane", "theta-fmax", "--chart", "none"}}) {
    args.insert(args.begin() + 1, scene.begin(), scene.end());
    testing_support::expect_rejected(args, {"load.profile = \"impulse\"", "load.approximation = \"exact\"",
                                            "no continuum limit", "load.profile = \"rectangular\""});
  }
}
