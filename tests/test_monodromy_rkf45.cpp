// --method monodromy-rkf45: the time domain's RKF45 stepper integrates Φ(T). Against the Magnus
// monodromy, an independent Runge–Kutta–Fehlberg 7(8) integration of the same periodic system with
// the cosine load (42) written here, and Liouville's det Φ(T) = exp(−∫₀ᵀ tr(M⁻¹C) dt) with the trace
// from the test's own modes; and through the program's `stability --method monodromy-rkf45`.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "reference/odeint_monodromy.hpp"
#include "support/json.hpp"
#include "support/run_cli.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

constexpr double pi = 3.14159265358979323846;

// The eigenvalues of Φ(T) for the cosine load (42), F(t) = −F_max/2 + (F_max/2) cos θt, by
// Fehlberg 7(8) at 1e-12 on A(t) = A₀ + (F(t) − F₀) B.
Eigen::VectorXcd reference_multipliers(const PeriodicSystem& sys, double peak) {
  const double theta = sys.angular_frequency, F0 = sys.coefficients[0].real();
  const Eigen::MatrixXd phi = reference::odeint_propagator(
      sys.A0, sys.B, [&](double t) { return -peak / 2 + peak / 2 * std::cos(theta * t) - F0; }, {}, sys.period(), 1e-12);
  return Eigen::EigenSolver<Eigen::MatrixXd>(phi, false).eigenvalues();
}

}  // namespace

TEST_CASE("monodromy-rkf45: max|rho| agrees with Magnus and with Runge-Kutta 7(8) within its estimate",
          "[stability][rkf45][long_under_sanitizers]") {
  // The paper blade, four terms, automatic reduction, cosine load: stable (F̄ = 1) and unstable (F̄ = 5).
  for (const double fbar : {1.0, 5.0}) {
    const Scene s = paper_scene({"model.terms=4", "load.fmax_over_fcr=" + std::to_string(fbar)});
    const BladeModel m = assemble_model(s);
    const PeriodicSystem sys = periodic_system(m, s, load_series(s));
    const double tol = 1e-5;
    const FloquetResult rkf = floquet_multipliers(sys, {FloquetMethod::monodromy_rkf45, 0, tol});
    const FloquetResult magnus = floquet_multipliers(sys, {FloquetMethod::monodromy, 0, 1e-10});
    const Eigen::VectorXcd reference = reference_multipliers(sys, fbar * m.blade.critical_load());
    const double rho = reference.cwiseAbs().maxCoeff();
    INFO("F̄ = " << fbar << ": RKF45 max|ρ| " << rkf.max_abs_multiplier << " (estimate " << rkf.error_estimate
                << "), Magnus " << magnus.max_abs_multiplier << ", Fehlberg 7(8) " << rho << "; whole set "
                << multiplier_set_distance(rkf.multipliers, reference));
    CHECK(rkf.method == FloquetMethod::monodromy_rkf45);
    CHECK(rkf.error_estimate <= tol * std::max(1.0, rho));
    CHECK(std::abs(rkf.max_abs_multiplier - rho) <= rkf.error_estimate);
    CHECK(multiplier_set_distance(rkf.multipliers, reference) <= rkf.error_estimate);
    CHECK(std::abs(rkf.max_abs_multiplier - magnus.max_abs_multiplier) <= rkf.error_estimate + magnus.error_estimate);
    CHECK(rkf.stable == (fbar < 3));
  }
}

TEST_CASE("monodromy-rkf45: det Phi(T) is Liouville's exp(-T tr(M^-1 C)) on the whole damped model",
          "[stability][rkf45][long_under_sanitizers]") {
  // Every mode of a small bending model (reduction "none"), modal damping ζ: the gyroscopic part of
  // C is skew and has no trace, M⁻¹C_D = Φ diag(2ζω_k) Φᵀ M has the trace Σ 2ζω_k.
  const double zeta = 0.002;
  const Scene s = paper_scene({"model.theory=euler-bernoulli", "model.axial=false", "model.terms=6",
                               "model.reduction=none", "damping.model=modal", "damping.ratio=0.002"});
  const BladeModel m = assemble_model(s);
  const PeriodicSystem sys = periodic_system(m, s, load_series(s));
  const Eigen::VectorXd omega =
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(m.stiffness(300), m.M, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .cwiseSqrt();
  REQUIRE(sys.state_size() == 2 * omega.size());
  const double log_det_reference = -sys.period() * 2 * zeta * omega.sum();
  const FloquetResult r = floquet_multipliers(sys, {FloquetMethod::monodromy_rkf45, 0, 1e-6});
  double log_det = 0;
  for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) log_det += std::log(std::abs(r.multipliers(k)));
  INFO("ln det Φ = " << log_det << ", Liouville " << log_det_reference << " (Σω = " << omega.sum()
                     << " rad/s): difference " << log_det - log_det_reference);
  CHECK(log_det_reference < -0.1);  // damping that shows in the determinant
  CHECK(std::abs(log_det - log_det_reference) < 1e-6);
}

TEST_CASE("stability --method monodromy-rkf45 through the program: the Magnus answer within both estimates",
          "[stability][rkf45][cli][parallel][long_under_sanitizers]") {
  const auto answer = [](const std::string& method) {
    const testing_support::Outcome o = testing_support::run_bladestab(
        {"stability", testing_support::paper_scene_path(), "--set", "model.terms=4", "--method", method, "--tolerance",
         "1e-4", "--format", "json"});
    INFO(method << ": " << testing_support::describe(o) << "\n" << o.err);
    REQUIRE(o.err.empty());
    return testing_support::parse_json(o.out);
  };
  const testing_support::Json rkf = answer("monodromy-rkf45"), magnus = answer("monodromy");
  const double rho = rkf["max_abs_multiplier"].number, reference = magnus["max_abs_multiplier"].number;
  INFO("max|ρ| " << rho << " ± " << rkf["error_estimate"].number << " (RKF45, " << rkf["terms"].number << " terms), "
                 << reference << " ± " << magnus["error_estimate"].number << " (Magnus, " << magnus["terms"].number
                 << " terms)");
  CHECK(rkf["method"].text == "monodromy-rkf45");
  CHECK(std::abs(rho - reference) <= rkf["error_estimate"].number + magnus["error_estimate"].number);
  CHECK(rkf["error_estimate"].number <= 1e-4 * rho);  // the tolerance, relative above max|ρ| = 1
  CHECK(rkf["error_budget"]["method"].number <= 1e-4 * rho / 4);  // the quarter of it the analysis gives the method
  // docs/theory.md §6: the paper point, F̄ = 5 at 300 rad/s, is unstable under the cosine load (max|ρ| 2.1992).
  CHECK(std::abs(rho - 2.1992) < 1e-3);
  CHECK_FALSE(rkf["stable"].boolean);
}
