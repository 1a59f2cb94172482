// Natural frequencies against closed-form references and the SPEC's converged values.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bladestab/blade/damping.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/modal/modes.hpp"
#include "reference/timoshenko_cantilever.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

constexpr double pi = 3.14159265358979323846;

ModalSolution modes_of(const Scene& s, int count = 0, EigenSolverKind solver = EigenSolverKind::dense) {
  const BladeModel m = assemble_model(s);
  const double W = s.operation.speed_rad_s;
  return solve_modes(m, system_at(m, W, damping_matrix(m, s.damping, W)), W, count, solver);
}

std::vector<double> lambdas(const ModalSolution& sol, bool want_axial, std::size_t count) {
  std::vector<double> out;
  for (const Mode& m : sol.modes) {
    if ((m.family == ModeFamily::axial) == want_axial && out.size() < count) out.push_back(m.lambda);
  }
  return out;
}

// Roots x of 1 + cos x cosh x = 0 (Euler–Bernoulli cantilever), by bisection: Λ = x².
double euler_bernoulli_lambda(int n) {
  double a = (n - 0.5) * pi - 0.5, b = (n - 0.5) * pi + 0.5;
  const auto f = [](double x) { return 1 + std::cos(x) * std::cosh(x); };
  for (int i = 0; i < 200; ++i) {
    const double c = 0.5 * (a + b);
    ((f(a) > 0) == (f(c) > 0) ? a : b) = c;
  }
  return 0.25 * (a + b) * (a + b);
}

}  // namespace

TEST_CASE("at rest, Legendre Ritz frequencies match Huang's closed-form Timoshenko cantilever", "[modes]") {
  const double E_over_kappaG = 2 * (1 + 0.3) / 0.833;
  for (double d : {0.01, 0.05, 0.1, 0.3}) {
    const Scene s = paper_scene({"operation.speed_rad_s=0", "model.terms=20", "blade.slenderness=" + std::to_string(d)});
    const std::vector<double> exact = reference::timoshenko_cantilever_lambdas(d, E_over_kappaG, 5);
    const std::vector<double> ours = lambdas(modes_of(s), false, 5);
    REQUIRE(ours.size() == 5);
    for (int k = 0; k < 5; ++k) {
      INFO("d = " << d << ", mode " << k + 1);
      CHECK(ours[k] == Approx(exact[k]).epsilon(1e-5));
    }
  }
}

TEST_CASE("the SPEC's closed-form values are what the reference gives", "[modes]") {
  const std::vector<double> d001 = reference::timoshenko_cantilever_lambdas(0.01, 2 * 1.3 / 0.833, 5);
  const std::vector<double> spec{3.51265, 21.8889, 60.7407, 117.515, 191.177};
  for (int k = 0; k < 5; ++k) CHECK(d001[k] == Approx(spec[k]).epsilon(5e-6));
}

TEST_CASE("axial modes are (2n-1)(pi/2)/d", "[modes]") {
  for (const char* basis : {"legendre", "sine"}) {
    const Scene s = paper_scene({"operation.speed_rad_s=0", std::string("model.basis=") + basis});
    const std::vector<double> ours = lambdas(modes_of(s), true, 3);
    REQUIRE(ours.size() == 3);
    for (int n = 1; n <= 3; ++n) {
      INFO(basis << " axial mode " << n);
      CHECK(ours[n - 1] == Approx((2 * n - 1) * (pi / 2) / 0.01).epsilon(1e-6));
    }
  }
  // Hz, docs/theory.md §7: 1279.6 and 3838.8.
  const ModalSolution sol = modes_of(paper_scene({"operation.speed_rad_s=0"}), 12);
  std::vector<double> hz;
  for (const Mode& m : sol.modes) if (m.family == ModeFamily::axial) hz.push_back(m.frequency_hz);
  CHECK(hz.at(0) == Approx(1279.6).epsilon(1e-4));
  CHECK(hz.at(1) == Approx(3838.8).epsilon(1e-4));
}

TEST_CASE("Euler-Bernoulli theory gives the classical cantilever values", "[modes]") {
  for (const char* basis : {"legendre", "sine"}) {
    const Scene s = paper_scene({"operation.speed_rad_s=0", "model.theory=euler-bernoulli", "model.axial=false",
                                 std::string("model.basis=") + basis});
    const std::vector<double> ours = lambdas(modes_of(s), false, 3);
    const double tolerance = std::string(basis) == "legendre" ? 1e-10 : 1e-3;  // sine: algebraic convergence
    for (int n = 1; n <= 3; ++n) {
      INFO(basis << " mode " << n);
      CHECK(ours[n - 1] == Approx(euler_bernoulli_lambda(n)).epsilon(tolerance));
    }
  }
  CHECK(euler_bernoulli_lambda(1) == Approx(3.51602).epsilon(2e-6));
  CHECK(euler_bernoulli_lambda(2) == Approx(22.0345).epsilon(2e-6));
  CHECK(euler_bernoulli_lambda(3) == Approx(61.6972).epsilon(2e-6));
}

TEST_CASE("rotating paper blade at 300 rad/s matches the SPEC's converged values", "[modes]") {
  const std::vector<double> coupled{8.3518, 28.9467, 68.5778, 126.004, 200.105};
  const std::vector<double> uncoupled{8.3573, 28.9497, 68.5802, 126.006, 200.107};
  for (bool coriolis : {true, false}) {
    const Scene s = paper_scene({std::string("model.coriolis=") + (coriolis ? "true" : "false"), "model.terms=24"});
    const ModalSolution sol = modes_of(s);
    const std::vector<double> ours = lambdas(sol, false, 5);
    const auto& expected = coriolis ? coupled : uncoupled;
    for (int k = 0; k < 5; ++k) {
      INFO("coriolis " << coriolis << ", mode " << k + 1);
      CHECK(ours[k] == Approx(expected[k]).epsilon(1e-4));
    }
    if (coriolis) CHECK(sol.modes[0].frequency_hz == Approx(68.035).epsilon(1e-5));  // docs/theory.md §7
    for (const Mode& m : sol.modes) CHECK(m.damping_ratio == 0);       // undamped: exactly imaginary
  }
}

TEST_CASE("convergence at d = 0.1, mode 3: Legendre exponential, sine algebraic", "[modes][convergence]") {
  // Against Huang's closed form (reference/timoshenko_cantilever.hpp). Ritz values are upper bounds,
  // so the error is Λ_N/Λ − 1 > 0 and falls with N (nested bases).
  const double exact = reference::timoshenko_cantilever_lambdas(0.1, 2 * 1.3 / 0.833, 3)[2];
  const auto error = [&](const char* basis, int terms) {
    const Scene s = paper_scene({"operation.speed_rad_s=0", "blade.slenderness=0.1", "model.axial=false",
                                 std::string("model.basis=") + basis, "model.terms=" + std::to_string(terms)});
    return lambdas(modes_of(s), false, 3)[2] / exact - 1;
  };
  std::ostringstream measured;
  // Legendre (p-version): the error falls at least geometrically, by more than ×30 for every two
  // terms added from 4 to 12 (measured ×54, ×205, ×603, ×1380), to rounding by 14.
  measured << "legendre:";
  std::vector<double> legendre;
  for (int terms = 4; terms <= 12; terms += 2) {
    legendre.push_back(error("legendre", terms));
    measured << " N = " << terms << ": " << legendre.back() << ";";
  }
  for (std::size_t i = 0; i + 1 < legendre.size(); ++i) {
    INFO("legendre N = " << 4 + 2 * i << ": " << legendre[i] << ", N + 2: " << legendre[i + 1]);
    CHECK(legendre[i] > 0);
    CHECK(legendre[i + 1] < legendre[i] / 30);
  }
  CHECK(std::abs(error("legendre", 14)) < 1e-10);
  // Sine (the paper's basis forces v'(0) = 0, which the sheared root does not have): algebraic,
  // e ≈ c N^−p with p fitted over N = 10, 20, 40 by least squares in log–log. Expected p = 1: the sine
  // series of a slope with v'(0) ≠ 0 has coefficients ~1/n, so the energy of its tail beyond N, and
  // with it the Ritz eigenvalue's error, falls like 1/N (measured p = 1.0025).
  measured << " sine:";
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const std::vector<int> sine_terms{10, 20, 40};
  double previous = 1;
  for (int terms : sine_terms) {
    const double e = error("sine", terms);
    measured << " N = " << terms << ": " << e << ";";
    INFO("sine N = " << terms << ": " << e);
    CHECK(e > 0);
    CHECK(e < previous);
    previous = e;
    const double x = std::log(terms), y = std::log(e);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double count = static_cast<double>(sine_terms.size());
  const double p = -(count * sxy - sx * sy) / (count * sxx - sx * sx);
  INFO("fitted algebraic rate p = " << p);
  CHECK(p > 0.9);
  CHECK(p < 1.1);
  WARN(measured.str() << " fitted sine rate " << p);
}

TEST_CASE("ARPACK shift-invert agrees with dense LAPACK", "[modes][arpack]") {
  for (const auto& damping : {std::vector<std::string>{"model.terms=50"},
                              std::vector<std::string>{"model.terms=50", "damping.model=rayleigh", "damping.ratio=0.02",
                                                       "damping.frequencies_hz=[50, 2000]"}}) {
    const Scene s = paper_scene(damping);
    const ModalSolution dense = modes_of(s, 8, EigenSolverKind::dense);
    const ModalSolution arpack = modes_of(s, 8, EigenSolverKind::arpack);
    REQUIRE(arpack.solver == EigenSolverKind::arpack);
    REQUIRE(arpack.modes.size() == 8);
    const BladeModel m = assemble_model(s);
    for (int k = 0; k < 8; ++k) {
      INFO(damping.size() << " overrides, mode " << k + 1);
      // Measured: at most 5e-13 over modes 1–8, damped or not (2e-9 on mode 8 before the first-order
      // form was balanced, arpack_modes.cpp).
      CHECK(std::abs(arpack.modes[k].eigenvalue - dense.modes[k].eigenvalue) < 1e-11 * std::abs(dense.modes[k].eigenvalue));
      CHECK(modal_assurance(arpack.modes[k].shape, dense.modes[k].shape, m.M) > 1 - 1e-8);
      CHECK(arpack.modes[k].family == dense.modes[k].family);
    }
  }
  // The automatic choice takes ARPACK for large models.
  CHECK(modes_of(paper_scene({"model.terms=50"}), 5, EigenSolverKind::automatic).solver == EigenSolverKind::arpack);
}

TEST_CASE("ARPACK on two threads at once: every solve as alone on a buckled and a diverged blade",
          "[modes][arpack][threads][slow]") {
  // 40 terms per field (120 dofs, ARPACK's size), Coriolis off so that each reference below is a
  // symmetric eigenproblem. Under 2 F_cr the blade buckles at rest; at 9000 rad/s its axial field
  // has diverged (past (π/2)·sqrt(E/ρ)/L = 8039.95 rad/s). Both stiffnesses are indefinite: the
  // solves that aborted `campbell --threads 2`.
  const std::vector<std::string> base{"model.terms=40", "model.coriolis=false"};
  std::vector<std::string> compressed = base;
  compressed.push_back("operation.tip_compression_over_fcr=2");
  const BladeModel loaded = assemble_model(paper_scene(compressed)), unloaded = assemble_model(paper_scene(base));
  const int n = loaded.layout.size();
  REQUIRE(n >= arpack_threshold_dofs);
  const Eigen::MatrixXd none = Eigen::MatrixXd::Zero(n, n);
  const SecondOrderSystem buckled = system_at(loaded, 0, none), diverged = system_at(unloaded, 9000, none);
  const Eigenpairs alone_buckled = arpack_eigenpairs(buckled, 8), alone_diverged = arpack_eigenpairs(diverged, 8);
  // Right: without C, λ² = −μ for the eigenvalues μ of K x = μ M x, so |λ| = sqrt|μ|, twice for
  // each μ < 0 (the real pair ±sqrt(−μ)) and once for each μ > 0 (one of ±i sqrt(μ)).
  for (const auto& [system, alone] : {std::pair{&buckled, &alone_buckled}, std::pair{&diverged, &alone_diverged}}) {
    const Eigen::VectorXd mu = Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(
                                   system->K, system->M, Eigen::EigenvaluesOnly).eigenvalues();
    REQUIRE(mu(0) < 0);
    std::vector<double> moduli;
    for (Eigen::Index j = 0; j < mu.size(); ++j) {
      moduli.insert(moduli.end(), mu(j) < 0 ? 2 : 1, std::sqrt(std::abs(mu(j))));
    }
    std::sort(moduli.begin(), moduli.end());
    REQUIRE(alone->values.size() == 8);
    for (int k = 0; k < 8; ++k) {
      const std::complex<double> lambda = alone->values(k);
      INFO("mode " << k + 1 << ": ARPACK " << lambda << ", sqrt|μ| " << moduli[k]);
      // Measured: 2e-12 on the buckled pair, 7e-8 on mode 8 (where the reference's own rounding,
      // ε·ω_max²/ω², is of the same order with 40 terms).
      CHECK(std::abs(lambda) == Approx(moduli[k]).epsilon(1e-6));
      // Real or imaginary, as the sign of μ says.
      CHECK(std::min(std::abs(lambda.real()), std::abs(lambda.imag())) <= 1e-9 * std::abs(lambda));
    }
  }
  // Eight solves on each of two threads at once; each equal to the solve alone, to the last bit.
  constexpr int repeats = 8;
  std::vector<Eigenpairs> on_helper, on_caller;
  std::thread helper([&] {
    for (int r = 0; r < repeats; ++r) on_helper.push_back(arpack_eigenpairs(buckled, 8));
  });
  for (int r = 0; r < repeats; ++r) on_caller.push_back(arpack_eigenpairs(diverged, 8));
  helper.join();
  for (int r = 0; r < repeats; ++r) {
    INFO("repeat " << r);
    CHECK(on_helper[r].values == alone_buckled.values);
    CHECK(on_helper[r].vectors == alone_buckled.vectors);
    CHECK(on_caller[r].values == alone_diverged.values);
    CHECK(on_caller[r].vectors == alone_diverged.vectors);
  }
}

TEST_CASE("damping models give the damping ratios they promise", "[modes][damping]") {
  // Modal damping at rest: every mode gets exactly ζ.
  const ModalSolution modal = modes_of(paper_scene({"operation.speed_rad_s=0", "damping.model=modal", "damping.ratio=0.03"}), 10);
  for (const Mode& m : modal.modes) CHECK(m.damping_ratio == Approx(0.03).epsilon(1e-9));
  // Rayleigh: ζ(ω) = α/(2ω) + βω/2 with ζ met at both given frequencies.
  const double f1 = 50, f2 = 2000, z = 0.02, w1 = 2 * pi * f1, w2 = 2 * pi * f2;
  const double alpha = 2 * z * w1 * w2 / (w1 + w2), beta = 2 * z / (w1 + w2);
  const ModalSolution ray = modes_of(paper_scene({"operation.speed_rad_s=0", "damping.model=rayleigh", "damping.ratio=0.02",
                                                  "damping.frequencies_hz=[50, 2000]"}), 6);
  for (const Mode& m : ray.modes) {
    const double wn = std::abs(m.eigenvalue);  // undamped natural frequency
    CHECK(m.damping_ratio == Approx(alpha / (2 * wn) + beta * wn / 2).epsilon(1e-9));
  }
  // Paper (37): C_D = (2ζ/Ω) K_S.
  const Scene p = paper_scene({"damping.model=paper", "damping.ratio=0.01"});
  const BladeModel m = assemble_model(p);
  // To rounding (the factor may be applied as one product or fused into two).
  const Eigen::MatrixXd expected = (2 * 0.01 / 300) * m.K_S;
  CHECK((damping_matrix(m, p.damping, 300) - expected).norm() <= 1e-15 * expected.norm());
}

TEST_CASE("heavy damping: an oscillating mode's counterpart in the richer model is an oscillating one",
          "[modes][damping][convergence]") {
  // Rayleigh ζ = 0.3 at 600 rad/s, 18 terms: mode 13, bending at 3103.89 Hz (ζ = 0.42), sits among
  // overdamped roots, more of them in the 27-term model; its counterpart there had been one of those
  // (error 1, the frequency printed to 3 digits). Against 40 terms, dense.
  const Scene s = paper_scene({"model.terms=18", "operation.speed_rad_s=600", "damping.model=rayleigh",
                               "damping.ratio=0.3", "damping.frequencies_hz=[50, 2000]"});
  const ConvergedModes c = modes_with_error_estimate(s, 20, EigenSolverKind::dense);
  ModelSpec rich = s.model;
  rich.terms = 40;
  const BladeModel m = assemble_model(s, rich);
  const ModalSolution truth = solve_modes(m, system_at(m, 600, damping_matrix(m, s.damping, 600)), 600, 0,
                                          EigenSolverKind::dense);
  int checked = 0;
  for (std::size_t k = 0; k < c.solution.modes.size(); ++k) {
    const double f = c.solution.modes[k].frequency_hz;
    if (f == 0) continue;  // overdamped
    double nearest = 1e300;
    for (const Mode& m : truth.modes) nearest = std::min(nearest, std::abs(m.frequency_hz / f - 1));
    INFO("mode " << k + 1 << ", " << f << " Hz");
    CHECK(c.budget(k).total() < 1e-6);
    CHECK(nearest <= c.budget(k).total());  // the basis part and the eigensolver's rounding
    ++checked;
  }
  CHECK(checked == 8);
}

TEST_CASE("error estimates are honest and --tolerance raises the number of terms", "[modes][convergence]") {
  const Scene s = paper_scene({"model.terms=8", "operation.speed_rad_s=0", "blade.slenderness=0.1", "model.axial=false"});
  const ConvergedModes loose = modes_with_error_estimate(s, 3, EigenSolverKind::dense);
  const double exact = reference::timoshenko_cantilever_lambdas(0.1, 2 * 1.3 / 0.833, 3)[2];
  const double true_error = std::abs(loose.solution.modes[2].lambda / exact - 1);
  // Exponential convergence: the change against the richer model is the error; the estimate adds 10 %.
  CHECK(loose.relative_error[2] >= true_error);
  CHECK(loose.relative_error[2] <= 1.15 * true_error);
  const ConvergedModes tight = modes_with_error_estimate(s, 3, EigenSolverKind::dense, 1e-9);
  CHECK(tight.model.spec.terms > 8);
  CHECK(tight.max_relative_error() <= 1e-9);
  CHECK(std::abs(tight.solution.modes[2].lambda / exact - 1) < 1e-9);
}

TEST_CASE("sine basis: the estimate from N, 2N, 4N covers the true error against the closed form", "[modes][convergence][long_under_sanitizers]") {
  const double E_over_kappaG = 2 * (1 + 0.3) / 0.833;
  double lowest_ratio = 1e300, highest_ratio = 0;
  for (double d : {0.01, 0.1}) {
    const std::vector<double> exact = reference::timoshenko_cantilever_lambdas(d, E_over_kappaG, 4);
    for (int terms : {10, 20, 40}) {
      const Scene s = paper_scene({"operation.speed_rad_s=0", "model.basis=sine", "model.axial=false",
                                   "blade.slenderness=" + std::to_string(d), "model.terms=" + std::to_string(terms)});
      const ConvergedModes c = modes_with_error_estimate(s, 4, EigenSolverKind::dense);
      REQUIRE(c.solution.modes.size() == 4);
      for (int k = 0; k < 4; ++k) {
        const double truth = std::abs(c.solution.modes[k].lambda / exact[k] - 1);
        const double ratio = c.budget(k).total() / truth;
        INFO("d = " << d << ", N = " << terms << ", mode " << k + 1 << ": estimate " << c.budget(k).total()
                    << ", true " << truth << ", ratio " << ratio);
        CHECK(ratio >= 1);
        CHECK(ratio < 2);  // and not so loose that it hides digits the result has
        lowest_ratio = std::min(lowest_ratio, ratio);
        highest_ratio = std::max(highest_ratio, ratio);
      }
    }
  }
  WARN("sine-basis estimate / true error: " << lowest_ratio << " to " << highest_ratio);
}
