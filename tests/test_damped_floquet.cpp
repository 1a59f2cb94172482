// Damped Floquet multipliers and log decrements, and the damping ratios `modes` reports, against
// references computed here:
//  - the damped Mathieu equation x'' + c x' + (a − 2q cos 2τ) x = 0 has the multipliers
//    e^{−cπ/2} × those of the undamped z'' + (a − c²/4 − 2q cos 2τ) z = 0 (x = e^{−cτ/2} z), whose
//    monodromy is integrated here (Runge–Kutta–Fehlberg 7(8)); on a boundary of the undamped
//    equation's first tongue (a − c²/4 = a₁(q) or b₁(q), tests/reference/mathieu.hpp) both
//    multipliers are −e^{−cπ/2};
//  - the unloaded blade with modal damping ζ and no Coriolis coupling: each mode decays by
//    e^{−ζωT} per period, log decrement (46) 2πζ/√(1 − ζ²);
//  - `modes`: −Re λ/|λ| of the quadratic eigenproblem with C_D built here from each damping
//    model's definition (damping.hpp, docs/theory.md §2), solved as a first-order eigenproblem of its own.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "reference/first_order_modes.hpp"
#include "reference/mathieu.hpp"
#include "reference/odeint_monodromy.hpp"
#include "support/json.hpp"
#include "support/run_cli.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

constexpr double pi = 3.14159265358979323846;

// A scene value to the last digit (std::to_string keeps six decimals).
std::string digits(double v) {
  std::ostringstream text;
  text << std::setprecision(17) << v;
  return text.str();
}

// One sine mode of the Euler–Bernoulli blade at rest under the cosine load (42) at θ = 2πf, with
// modal damping ζ: q̈ + 2ζω₀ q̇ + (K + F(t) G)/M q = 0, F(t) = −F_max/2 + (F_max/2) cos θt.
Scene one_dof_scene(double fbar, double zeta, double pulse_hz) {
  return paper_scene({"model.theory=euler-bernoulli", "model.terms=1", "model.axial=false", "model.basis=sine",
                      "operation.speed_rad_s=0", "load.approximation=cosine",
                      "load.fmax_over_fcr=" + digits(fbar), "damping.model=modal", "damping.ratio=" + digits(zeta),
                      "load.pulse_frequency_hz=" + digits(pulse_hz)});
}

// The one-dof scene as a damped Mathieu equation in τ = θt/2 (from its 1×1 model matrices):
// a = (4/θ²)(K − G F_max/2)/M, q = −(4/θ²) G F_max/(4M), c = 4ζω₀/θ, ω₀² = K/M.
struct DampedMathieu {
  double a, q, c;
};

DampedMathieu mathieu_form(const Scene& s) {
  const BladeModel m = assemble_model(s);
  const double K = m.stiffness(0)(0, 0), M = m.M(0, 0), G = m.G(0, 0);
  const double F = s.load.fmax_over_fcr * pi * pi * s.blade.youngs_modulus * s.blade.inertia / (4 * s.blade.length * s.blade.length);
  const double theta = 2 * pi * *s.load.pulse_frequency_hz, x = 4 / (theta * theta);
  return {x * (K - G * F / 2) / M, -x * G * F / (4 * M), 4 * s.damping.ratio * std::sqrt(K / M) / theta};
}

// e^{−cπ/2} × the eigenvalues of the undamped equation's monodromy over τ ∈ [0, π].
Eigen::VectorXcd damped_mathieu_multipliers(const DampedMathieu& e) {
  Eigen::Matrix2d A0, B;
  A0 << 0, 1, -(e.a - e.c * e.c / 4), 0;
  B << 0, 0, 2 * e.q, 0;  // A(τ) = A₀ + cos 2τ · B
  const Eigen::MatrixXd phi =
      reference::odeint_propagator(A0, B, [](double tau) { return std::cos(2 * tau); }, {}, pi, 1e-13);
  return Eigen::EigenSolver<Eigen::MatrixXd>(phi, false).eigenvalues() * std::exp(-e.c * pi / 2);
}

// The root of g in [lo, hi], where g changes sign.
double bisect(const std::function<double(double)>& g, double lo, double hi) {
  const bool rising = g(hi) > 0;
  REQUIRE(rising != (g(lo) > 0));
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((g(mid) > 0) == rising ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// −Re λ/|λ| of (λ²M + λC + K) q = 0 for every λ with Im λ ≥ 0, as (frequency Im λ/2π [Hz], ratio)
// pairs sorted by frequency, from the first-order form in the test's own scaled modal coordinates
// (reference/first_order_modes.hpp): a general eigensolve of its own.
std::vector<std::pair<double, double>> damping_ratios(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                                                      const Eigen::MatrixXd& K) {
  std::vector<std::pair<double, double>> out;
  for (const std::complex<double>& l : reference::FirstOrderModes(M, C, K).eigenvalues()) {
    if (l.imag() >= 0) out.emplace_back(l.imag() / (2 * pi), -l.real() / std::abs(l));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("damped Mathieu: the multipliers are e^(-c pi/2) times the undamped ones with a - c^2/4",
          "[stability][damping][mathieu]") {
  // Stable and unstable points of the first two tongues, light and heavier damping.
  for (const double zeta : {0.01, 0.05}) {
    for (const auto [fbar, theta_over_w0] : {std::pair{0.6, 2.0}, std::pair{0.6, 1.3}, std::pair{1.2, 2.0},
                                            std::pair{1.2, 1.0}, std::pair{1.2, 3.0}}) {
      const Scene probe = one_dof_scene(fbar, zeta, 1);
      const BladeModel m = assemble_model(probe);
      const double w0 = std::sqrt(m.stiffness(0)(0, 0) / m.M(0, 0));
      const Scene s = one_dof_scene(fbar, zeta, theta_over_w0 * w0 / (2 * pi));
      const PeriodicSystem sys = periodic_system(m, s, load_series(s));
      const Eigen::VectorXcd reference = damped_mathieu_multipliers(mathieu_form(s));
      for (const FloquetMethod method : {FloquetMethod::monodromy, FloquetMethod::koopman_hill}) {
        const FloquetResult r = floquet_multipliers(sys, {method, 0, 1e-10});
        const double distance = multiplier_set_distance(r.multipliers, reference);
        INFO("ζ = " << zeta << ", F̄ = " << fbar << ", θ/ω₀ = " << theta_over_w0 << ", " << to_string(method)
                    << ": max|ρ| " << r.max_abs_multiplier << " (reference " << reference.cwiseAbs().maxCoeff()
                    << "), set distance " << distance);
        CHECK(distance < 1e-9);  // measured up to 2e-11
        CHECK(r.stable == (reference.cwiseAbs().maxCoeff() < 1));
      }
    }
  }
}

TEST_CASE("damped Mathieu on the first tongue's boundary of a - c^2/4: both multipliers are -e^(-c pi/2)",
          "[stability][damping][mathieu]") {
  const double zeta = 0.03;
  for (const double fbar : {0.4, 1.0}) {
    const Scene probe = one_dof_scene(fbar, zeta, 1);
    const BladeModel m = assemble_model(probe);
    const double w0 = std::sqrt(m.stiffness(0)(0, 0) / m.M(0, 0));
    // The Mathieu form is linear in x = 4/θ²: a' = a − c²/4 = x·α, q = x·γ.
    const DampedMathieu unit = mathieu_form(probe);
    const double x_unit = 4 / std::pow(2 * pi * 1.0, 2);
    const double alpha = (unit.a - unit.c * unit.c / 4) / x_unit, gamma = unit.q / x_unit;
    for (const reference::MathieuKind kind : {reference::MathieuKind::a_odd, reference::MathieuKind::b_odd}) {
      const double x = bisect([&](double xx) { return xx * alpha - reference::mathieu(kind, 0, xx * gamma); },
                              0.3 / (w0 * w0), 10 / (w0 * w0));
      const double theta = 2 / std::sqrt(x);
      const Scene s = one_dof_scene(fbar, zeta, theta / (2 * pi));
      const FloquetResult r = floquet_multipliers(periodic_system(m, s, load_series(s)), {FloquetMethod::monodromy, 0, 1e-7});
      const double expected = -std::exp(-mathieu_form(s).c * pi / 2);
      const std::complex<double> mean = (r.multipliers(0) + r.multipliers(1)) / 2.0;
      const std::complex<double> product = r.multipliers(0) * r.multipliers(1);
      const double split = std::max(std::abs(r.multipliers(0) - expected), std::abs(r.multipliers(1) - expected));
      INFO("F̄ = " << fbar << ", boundary " << (kind == reference::MathieuKind::a_odd ? "a1" : "b1") << " at θ = "
                  << theta / w0 << " ω₀, expected ρ = " << expected << ": mean off by " << std::abs(mean - expected)
                  << ", product by " << std::abs(product - expected * expected) << ", each by up to " << split);
      // The pair's mean and product are smooth in Φ: −e^{−cπ/2} and e^{−cπ} (the undamped trace is −2
      // on the boundary, its determinant 1).
      CHECK(std::abs(mean - expected) < 1e-12);  // measured 1.4e-14
      CHECK(std::abs(product - expected * expected) < 1e-12);  // measured 2.6e-14
      // Each is a double multiplier with one eigenvector: an error ε of Φ moves it by about √ε.
      for (Eigen::Index k = 0; k < 2; ++k) CHECK(std::abs(r.multipliers(k) - expected) < 1e-6);  // measured 1.1e-7
    }
  }
}

TEST_CASE("unloaded blade with modal damping: decay e^(-zeta omega T) per period, log decrement 2 pi zeta/sqrt(1-zeta^2)",
          "[stability][damping]") {
  const double zeta = 0.02;
  // Coriolis off, so modal damping stays classical (the gyroscopic coupling would mix the ratios).
  // The pulse frequency θ = 2π·1200 Hz sets the period; F̄ = 0 leaves the blade unloaded. With
  // θ/2 above the kept modes' frequencies the exponents' Im λ are the modes' own, unfolded.
  const Scene s = paper_scene({"model.terms=6", "model.coriolis=false", "load.fmax_over_fcr=0", "damping.model=modal",
                               "damping.ratio=0.02", "load.pulse_frequency_hz=1200"});
  const BladeModel m = assemble_model(s);
  const PeriodicSystem sys = periodic_system(m, s, load_series(s));
  const FloquetResult r = floquet_multipliers(sys, {FloquetMethod::monodromy, 0, 1e-10});
  const double T = 1.0 / 1200;
  // The test's own undamped modes of K(Ω), M.
  const Eigen::VectorXd omega =
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(m.stiffness(300), m.M, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .cwiseSqrt();
  const int kept = sys.kept_modes;
  REQUIRE(kept >= 3);
  REQUIRE(r.multipliers.size() == 2 * kept);
  REQUIRE(omega(kept - 1) < pi / T);
  for (int k = 0; k < kept; ++k) {
    const double decay = std::exp(-zeta * omega(k) * T);  // |ρ| of mode k, both of its pair
    int matched = 0;
    for (Eigen::Index j = 0; j < r.multipliers.size(); ++j) {
      if (std::abs(std::abs(r.multipliers(j)) - decay) > 1e-9) continue;
      ++matched;
      // The pair's angle is the damped frequency ω√(1 − ζ²) T.
      CHECK(std::abs(std::arg(r.multipliers(j))) == Approx(omega(k) * std::sqrt(1 - zeta * zeta) * T).epsilon(1e-9));
      REQUIRE(r.log_decrements[j].has_value());
      CHECK(*r.log_decrements[j] == Approx(2 * pi * zeta / std::sqrt(1 - zeta * zeta)).epsilon(1e-9));
    }
    INFO("mode " << k + 1 << ": ω = " << omega(k) << " rad/s, |ρ| = e^(−ζωT) = " << decay);
    CHECK(matched == 2);
  }
}

TEST_CASE("the CLI's log decrements: 2 pi zeta/sqrt(1-zeta^2) to their printed digits, null where the multiplier "
          "is not resolved", "[stability][damping]") {
  const std::vector<std::string> base{"model.terms=6", "model.coriolis=false", "load.fmax_over_fcr=0",
                                      "damping.model=modal", "damping.ratio=0.999"};
  const auto decrements = [&](const std::string& pulse_frequency) {
    std::vector<std::string> args{"stability", testing_support::paper_scene_path(), "--format", "json"};
    for (const std::string& key : base) args.insert(args.end(), {"--set", key});
    args.insert(args.end(), {"--set", "load.pulse_frequency_hz=" + pulse_frequency});
    const testing_support::Outcome o = testing_support::run_bladestab(args);
    INFO(testing_support::describe(o) << "\n" << o.err);
    REQUIRE(o.err.empty());
    return testing_support::parse_json(o.out);
  };
  // θ/2 above the kept modes (as above): every pair's decrement is the closed form, 140.4.
  const testing_support::Json fast = decrements("1200");
  const double closed_form = 2 * pi * 0.999 / std::sqrt(1 - 0.999 * 0.999);
  int complex_pairs = 0;
  for (std::size_t k = 0; k < fast["log_decrements"].size(); ++k) {
    if (fast["log_decrements"][k].type == testing_support::Json::Type::null) continue;
    ++complex_pairs;
    CHECK(std::abs(fast["log_decrements"][k].number - closed_form) < 0.01 * closed_form);
  }
  CHECK(complex_pairs >= 6);
  // A period 12× longer: the stiffer modes' multipliers, e^(−ζωT) < 1e-8, lie within the estimate of
  // 0. Their decrements are unknown above a bound, null, never a rounded 0 (a damped mode's δ > 0).
  const testing_support::Json slow = decrements("100");
  int unresolved = 0;
  for (std::size_t k = 0; k < slow["log_decrements"].size(); ++k) {
    // Unloaded, each mode a damped oscillator (ζ < 1): no multiplier is real.
    if (slow["log_decrements"][k].type == testing_support::Json::Type::null) {
      ++unresolved;
      continue;
    }
    CAPTURE(k);
    CHECK(std::abs(slow["log_decrements"][k].number - closed_form) < 0.01 * closed_form);
  }
  CHECK(unresolved > 0);
}

TEST_CASE("modes: the damping ratio of every damping model is -Re(lambda)/|lambda| of its definition's C_D",
          "[modes][damping]") {
  // Six terms at 300 rad/s with Coriolis coupling: the gyroscopic C_G mixes into every model.
  const std::vector<std::string> base{"model.terms=6", "damping.ratio=0.02"};
  const BladeModel m = assemble_model(paper_scene({"model.terms=6"}));
  const double speed = 300, zeta = 0.02;
  const Eigen::MatrixXd K = m.stiffness(speed);
  // C_D by each definition (damping.hpp, docs/theory.md §2 and (37)).
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> undamped(K, m.M);
  const Eigen::MatrixXd Phi = undamped.eigenvectors();
  const Eigen::VectorXd two_zeta_omega = 2 * zeta * undamped.eigenvalues().cwiseSqrt();
  const double w1 = 2 * pi * 50, w2 = 2 * pi * 2000;  // Rayleigh: ζ met at 50 Hz and 2 kHz
  const double alpha = 2 * zeta * w1 * w2 / (w1 + w2), beta = 2 * zeta / (w1 + w2);
  const std::vector<std::tuple<std::string, std::vector<std::string>, Eigen::MatrixXd>> models{
      {"modal", {"damping.model=modal"}, m.M * Phi * two_zeta_omega.asDiagonal() * Phi.transpose() * m.M},
      {"rayleigh", {"damping.model=rayleigh", "damping.frequencies_hz=[50, 2000]"}, alpha * m.M + beta * m.K_S},
      {"paper", {"damping.model=paper"}, (2 * zeta / speed) * m.K_S}};
  for (const auto& [name, keys, C_D] : models) {
    const auto reference = damping_ratios(m.M, C_D + m.gyroscopic(speed), K);
    // Every digit: the damping ratios of the same 6-term model, compared far below its estimate.
    std::vector<std::string> args{"modes", testing_support::paper_scene_path(), "--count", "5", "--format", "json",
                                  "--digits", "full"};
    for (const std::string& key : base) args.insert(args.end(), {"--set", key});
    for (const std::string& key : keys) args.insert(args.end(), {"--set", key});
    const testing_support::Outcome o = testing_support::run_bladestab(args);
    INFO(name << ": " << testing_support::describe(o) << "\n" << o.err);
    REQUIRE(o.err.empty());
    const testing_support::Json j = testing_support::parse_json(o.out);
    CHECK(j["damping"].text == name);
    REQUIRE(j["modes"].size() == 5);
    for (std::size_t k = 0; k < 5; ++k) {
      const double f = j["modes"][k]["frequency_hz"].number, ratio = j["modes"][k]["damping_ratio"].number;
      const auto& nearest = *std::min_element(reference.begin(), reference.end(), [f](const auto& a, const auto& b) {
        return std::abs(a.first - f) < std::abs(b.first - f);
      });
      INFO("mode " << k + 1 << " at " << f << " Hz (reference " << nearest.first << " Hz): ζ = " << ratio
                   << ", reference " << nearest.second);
      CHECK(nearest.first == Approx(f).epsilon(1e-9).margin(1e-9));  // an overdamped mode is at 0 Hz
      CHECK(ratio == Approx(nearest.second).epsilon(1e-8));
    }
  }
}
