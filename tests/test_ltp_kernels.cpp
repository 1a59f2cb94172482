// The LTP kernels on Mathieu's equation stated directly, no blade type:
//
//   y'' + c y' + (a − 2q cos 2τ) y = 0,
//
// as the modal form η̈ + C η̇ + (Λ + f(τ) G) η = 0 with Λ = a, G = 1, C = c, f(τ) = −2q cos 2τ
// (f₁ = −q), θ = 2, period π. Every Floquet method and the boundary equations are checked against
// Mathieu's characteristic values (tests/reference/mathieu.hpp, an independent eigen-solve of the
// recurrences). On a boundary a = a_n(q) or b_n(q) the two multipliers meet at (−1)ⁿ; their sum,
// the trace of Φ(π), is smooth there (the multipliers of a Jordan pair are not), so the tests
// compare ρ₁ + ρ₂ with ±2. With damping, y = e^{−cτ/2} z turns the equation into Mathieu's with
// a − c²/4, and the multipliers scale by e^{−cπ/2}.
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include <catch2/catch.hpp>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/boundary_equations.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/ltp/linear_periodic_system.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "bladestab/ltp/pulse_monodromy.hpp"
#include "bladestab/ltp/reversing_symmetry.hpp"
#include "bladestab/ltp/step_doubling.hpp"
#include "reference/mathieu.hpp"

using namespace bladestab;
using reference::MathieuKind;

namespace {

constexpr double pi = 3.14159265358979323846;

LinearPeriodicSystem mathieu(double a, double q, double c = 0) {
  ModalForm form{Eigen::VectorXd::Constant(1, a), Eigen::MatrixXd::Ones(1, 1), Eigen::MatrixXd::Constant(1, 1, c)};
  return modal_periodic_system(form, {0.0, -q}, 2.0, c == 0);
}

// The root of f on [lo, hi] (a sign change) by bisection to rounding.
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  double flo = f(lo);
  REQUIRE((flo < 0) != (f(hi) < 0));
  for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi), fmid = f(mid);
    if ((fmid < 0) == (flo < 0)) {
      lo = mid, flo = fmid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

struct Edge {
  MathieuKind kind;
  int r;       // 0-based index of the characteristic value
  int sign;    // the multiplier on the boundary: −1 for a₁, b₁; +1 for a₂, b₂
  int order;   // n: the edge belongs to the region at θ ≈ 2ω/n
};

const Edge edges[] = {{MathieuKind::b_odd, 0, -1, 1}, {MathieuKind::a_odd, 0, -1, 1},
                      {MathieuKind::b_even, 0, 1, 2}, {MathieuKind::a_even, 1, 1, 2}};

const FloquetMethod methods[] = {FloquetMethod::hill, FloquetMethod::koopman_hill, FloquetMethod::monodromy,
                                 FloquetMethod::monodromy_rkf45};

// On a boundary the two multipliers form a Jordan pair, each known only to √ of the method's
// error in Φ: the Hill methods' truncations (whose Φ settles to ~1e-10) agree there to ~1e-5 as
// sets, the monodromies' to 1e-6. Their sum, the trace of Φ, is smooth: within 2e-6 for all.
double boundary_tolerance(FloquetMethod method) {
  return method == FloquetMethod::hill || method == FloquetMethod::koopman_hill ? 1e-4 : 1e-6;
}

}  // namespace

TEST_CASE("LTP kernels on Mathieu: every Floquet method puts the multipliers' sum at ±2 on a_1, b_1, a_2, b_2",
          "[ltp][mathieu]") {
  for (const double q : {0.5, 1.5}) {
    for (const Edge& e : edges) {
      const double a = reference::mathieu(e.kind, e.r, q);
      if (a < 0.1) continue;  // the modal form needs ω² = a > 0
      for (const FloquetMethod method : methods) {
        INFO("q = " << q << ", a = " << a << ", " << to_string(method));
        const FloquetResult r = floquet_multipliers(mathieu(a, q), {method, 0, boundary_tolerance(method)});
        REQUIRE(r.multipliers.size() == 2);
        CHECK(std::abs(r.multipliers.sum() - 2.0 * e.sign) <= 2e-6);
        // Liouville: det Φ = 1 undamped.
        CHECK(std::abs(r.multipliers.prod() - 1.0) <= 2e-6);
      }
    }
  }
}

TEST_CASE("LTP kernels on Mathieu: inside the first tongue the system is unstable, outside stable, by every method",
          "[ltp][mathieu]") {
  const double q = 1;
  const double a1 = reference::mathieu(MathieuKind::a_odd, 0, q), b2 = reference::mathieu(MathieuKind::b_even, 0, q);
  for (const FloquetMethod method : methods) {
    INFO(to_string(method));
    // Inside a −1 tongue the exponents μ ± i and −μ ± i all have |Im λ| = θ/2: the classical
    // sorting may keep a wrong pair, and the kernel then refuses (its monodromy check) rather than
    // answer; every other method answers.
    bool unstable = false, refused = false;
    try {
      unstable = !floquet_multipliers(mathieu(a1 - 0.2, q), {method, 0, 1e-8}).stable;
    } catch (const NumericalError&) {
      refused = true;
    }
    CHECK((unstable || (refused && method == FloquetMethod::hill)));
    const FloquetResult stable = floquet_multipliers(mathieu(0.5 * (a1 + b2), q), {method, 0, 1e-8});
    CHECK(stable.stable);
    CHECK(stable.max_abs_multiplier == Approx(1).margin(1e-7));
    // The undamped system was stated Hamiltonian: its multipliers were checked to be reciprocal.
    CHECK(stable.checks.reciprocal_error <= 1e-6);
  }
}

TEST_CASE("LTP kernels on damped Mathieu: on the boundary of a − c²/4 the sum is ±2 e^(−cπ/2), det Φ = e^(−cπ)",
          "[ltp][mathieu]") {
  const double q = 1, c = 0.2;
  for (const Edge& e : edges) {
    const double a = reference::mathieu(e.kind, e.r, q) + c * c / 4;
    if (a < 0.1) continue;
    for (const FloquetMethod method : methods) {
      INFO("a = " << a << ", " << to_string(method));
      const FloquetResult r = floquet_multipliers(mathieu(a, q, c), {method, 0, boundary_tolerance(method)});
      CHECK(std::abs(r.multipliers.sum() - 2.0 * e.sign * std::exp(-c * pi / 2)) <= 2e-6);
      CHECK(std::abs(r.multipliers.prod() - std::exp(-c * pi)) <= 2e-6);
      CHECK(std::isnan(r.checks.reciprocal_error));  // not stated Hamiltonian: no pairs to check
    }
  }
}

TEST_CASE("LTP kernels on Mathieu: the boundary equations in the amplitude give q where a_n(q) = a", "[ltp][mathieu]") {
  // θ = 2 and f₁ = −s: the amplitude s is Mathieu's q. At a = 1.5, a₁(q) crosses a twice (it
  // rises to ~1.9 and falls) and b₂(q) once, each bracketed here.
  const double a = 1.5;
  struct Crossing {
    Edge edge;
    double lo, hi;
  };
  const Crossing crossings[] = {{edges[1], 0.01, 2}, {edges[1], 3, 5.7}, {edges[2], 4, 7}};
  for (const int k : {8, 12}) {
    const std::vector<Boundary> found = boundary_loads(mathieu(a, 1), 1.0, 2.0, k);
    for (const Crossing& c : crossings) {
      const double q = bisect([&](double x) { return reference::mathieu(c.edge.kind, c.edge.r, x) - a; }, c.lo, c.hi);
      INFO("k = " << k << ", edge of order " << c.edge.order << " at q = " << q);
      bool matched = false;
      for (const Boundary& b : found) {
        if (b.multiplier == c.edge.sign && std::abs(b.peak_force_n - q) <= 1e-8 * q) matched = true;
      }
      CHECK(matched);
    }
  }
}

TEST_CASE("LTP kernels on Mathieu: the boundary equations in θ give 4ω²/θ² = a_n(4s/θ²), checked by the multipliers",
          "[ltp][mathieu]") {
  // y'' + (ω² − 2s cos θt) y = 0 is Mathieu's with τ = θt/2, a = 4ω²/θ², q = 4s/θ².
  const double w2 = 1, s = 0.3;
  const LinearPeriodicSystem system = mathieu(w2, s);
  for (const int k : {8, 12}) {
    const std::vector<Boundary> found = boundary_frequencies(system, s, k);
    for (const Edge& e : edges) {
      const double theta = bisect(
          [&](double t) { return 4 * w2 / (t * t) - reference::mathieu(e.kind, e.r, 4 * s / (t * t)); },
          e.order == 1 ? 1.2 : 0.6, e.order == 1 ? 4.0 : 1.6);
      INFO("k = " << k << ", order " << e.order << " edge at θ = " << theta);
      const Boundary* match = nullptr;
      for (const Boundary& b : found) {
        if (b.multiplier == e.sign && b.order == e.order && std::abs(b.theta_rad_s - theta) <= 1e-8 * theta) match = &b;
      }
      REQUIRE(match != nullptr);
      // The monodromy at the boundary has a multiplier at ±1 (a Jordan pair: √ of Φ's error).
      CHECK(multiplier_gap(system, s, *match, 1e-12).gap.value() <= 1e-5);
    }
  }
}

TEST_CASE("LTP kernels: a pulsed coefficient's monodromy is the product of the pulse's and the flight's exponentials",
          "[ltp][pulse]") {
  // y'' + (1 + f(t)) y = 0 with f = −0.5 on [0, 0.3) of each period 2: piecewise constant, so
  // Φ = e^{A_free (T − t_c)} e^{(A_free + f B) t_c} exactly.
  LinearPeriodicSystem system = mathieu(1, 0);
  system.angular_frequency = pi;
  system.coefficients = {0.0};
  const PeriodicPulse pulse{2.0, 0.3, [](double) { return -0.5; }, {}};
  const PulseMonodromy p = exact_pulse_monodromy(system, pulse, 1e-12);
  const Eigen::MatrixXd A = free_state_matrix(system);
  const auto expm2 = [](const Eigen::Matrix2d& m, double t) {
    // e^{mt} for m = [[0, w], [−k/w, 0]]: a rotation of frequency √k.
    const double w = m(0, 1), k = -m(1, 0) * w, r = std::sqrt(k);
    Eigen::Matrix2d e;
    e << std::cos(r * t), w / r * std::sin(r * t), -r / w * std::sin(r * t), std::cos(r * t);
    return e;
  };
  const Eigen::Matrix2d expected = expm2(A, 1.7) * expm2(A - 0.5 * system.B, 0.3);
  CHECK((p.monodromy - expected).cwiseAbs().maxCoeff() <= 1e-11);
}

TEST_CASE("LTP kernels: a long Fourier series sums to its closed form", "[ltp]") {
  // f_m = r^m e^{imφ} for m = 0..M: Σ_{|m|≤M} f_m e^{imθt} = 1 + 2 Re[z(1 − z^M)/(1 − z)] with
  // z = r e^{i(φ+θt)}, evaluated in 40 digits (mpmath) for r = 0.999, φ = 0.3, θ = 314, M = 3000.
  // Within 1e-12 absolute: 5e-16 of Σ|f_m| ≈ 2000, the rounding of the terms' sum.
  const double r = 0.999, phase = 0.3, theta = 314.0;
  std::vector<std::complex<double>> coefficients;
  for (int m = 0; m <= 3000; ++m) coefficients.push_back(std::polar(std::pow(r, m), m * phase));
  const std::pair<double, double> expected[] = {{0.0, 0.35382047180081983439},
                                                 {1e-3, 0.16523595494187954744},
                                                 {0.0123, -0.042144409596079586026},
                                                 {7.5, 0.09914185794258190093}};
  for (const auto& [t, sum] : expected) {
    CAPTURE(t);
    CHECK(std::abs(fourier_sum(coefficients, theta, t) - sum) <= 1e-12);
  }
}

TEST_CASE("LTP kernels: a pulse whose growth passes the double range stops as overflow at the safe count",
          "[ltp][pulse]") {
  // y'' + (1 + f) y = 0 with f = −1e6 on [0, 0.8) of each period 2: during the pulse y grows like
  // e^{√(1e6 − 1) t}, e^{800} ≈ 1e347 > 1e308 over it, at every step count (f is constant, so each
  // Magnus level is exact). The ladder must stop there, not climb to its last level.
  LinearPeriodicSystem system = mathieu(1, 0);
  system.angular_frequency = pi;
  system.coefficients = {0.0};
  const PeriodicPulse pulse{2.0, 0.8, [](double) { return -1e6; }, {}};
  CHECK_THROWS_WITH(exact_pulse_monodromy(system, pulse, 1e-8), Catch::Contains("overflows the double range"));
  // Over 0.3 the same pulse stays finite (e^{300}) and converges. Φ = R(1.7) H(0.3) with R the unit
  // rotation and H = [[ch, sh/s], [s sh, ch]] (s = √(1e6 − 1), x = 0.3 s); det Φ = 1, so
  // max ρ = tr Φ (to e^{−2x}) = 2 cos(1.7) ch + sin(1.7) sh (s − 1/s), whose log is
  // x + ln((2 cos 1.7 + sin 1.7 (s − 1/s)) / 2).
  const PeriodicPulse shorter{2.0, 0.3, [](double) { return -1e6; }, {}};
  const PulseMonodromy p = exact_pulse_monodromy(system, shorter, 1e-8);
  const double s = std::sqrt(1e6 - 1), x = 0.3 * s;
  const double expected = x + std::log((2 * std::cos(1.7) + std::sin(1.7) * (s - 1 / s)) / 2);
  CHECK(std::log(p.multipliers.cwiseAbs().maxCoeff()) == Approx(expected).epsilon(1e-10));
}

TEST_CASE("step doubling: a sixth-order ladder is accepted with the bound Δ/15 only on evidence", "[ltp]") {
  // Levels x_N = x* + E N⁻⁶: Δ_N = 63 E N⁻⁶ and the error of level N is E N⁻⁶ = Δ_N/63 ≤ Δ_N/15.
  const double E = 1e6;
  const auto error_at = [&](int N) { return E * std::pow(N, -6.0); };
  StepDoubling ladder(8, 1 << 17, 1 << 20);
  std::optional<double> accepted;
  int steps = 16;
  for (; steps <= ladder.last() && !accepted; steps *= 2) {
    accepted = ladder.judge(steps, error_at(steps / 2) - error_at(steps), 1e-6);
  }
  REQUIRE(accepted);
  const int at = steps / 2;
  CHECK(*accepted >= error_at(at));
  CHECK(*accepted <= 1e-6);

  SECTION("two levels that agree by chance are not enough") {
    StepDoubling fresh(8, 1 << 17, 1 << 20);
    CHECK_FALSE(fresh.judge(16, 1e-3, 1e-6));
    CHECK_FALSE(fresh.judge(32, 1e-7, 1e-6));  // within tol, but r = 1e4: the level before was pre-asymptotic
    CHECK(*fresh.judge(64, 1e-9, 1e-6) == Approx(1e-9 / 15));  // r = 100: asymptotic
  }
  SECTION("past the safe count one agreement suffices, and start() forgets the evidence") {
    StepDoubling safe(8, 1 << 17, 16);
    CHECK(safe.judge(16, 1e-9, 1e-6) == Approx(1e-9));
    StepDoubling restarted(8, 1 << 17, 1 << 20);
    CHECK_FALSE(restarted.judge(16, 5e-5, 1e-6));
    restarted.start();
    CHECK_FALSE(restarted.judge(32, 5e-7, 1e-6));  // r would be 100, but the evidence was forgotten
  }
  SECTION("an overflow restarts the evidence; two in a row from the safe count on are growth") {
    StepDoubling ladder(8, 1 << 17, 32);
    CHECK_FALSE(ladder.overflowed(8));
    CHECK_FALSE(ladder.overflowed(16));  // too long a step, twice: not yet evidence of growth
    CHECK_FALSE(ladder.overflowed(32));
    CHECK(ladder.overflowed(64));
    StepDoubling recovered(8, 1 << 17, 32);
    CHECK_FALSE(recovered.overflowed(32));
    CHECK_FALSE(recovered.judge(64, 1.0, 1e-6));  // a finite level between the two
    CHECK_FALSE(recovered.overflowed(128));
  }
  SECTION("a work limit keeps the levels whose steps together fit, and at least two") {
    // Levels 8, 16, 32 take 56 steps; with 64 they would take 120.
    const auto last_level = [](int last, double step_work, double max_work) {
      return StepDoubling(8, last, 1 << 20, step_work, max_work).last();
    };
    CHECK(last_level(1 << 17, 1.0, 100) == 32);
    CHECK(last_level(1 << 17, 2.0, 112) == 32);
    CHECK(last_level(1 << 17, 1.0, 24) == 16);
    CHECK(last_level(1 << 17, 1.0, 23) == 0);
    CHECK(last_level(16, 1.0, 1e9) == 16);
    CHECK(last_level(1 << 17, 1.0, std::numeric_limits<double>::infinity()) == 1 << 17);
    // The failure names what stopped the ladder: the work bound, or the most steps (from a first
    // level that is no power of two the last level, 102400, lies below the most, 2^17).
    CHECK_THROWS_AS(StepDoubling(8, 1 << 17, 1 << 20, 1.0, 100).give_up("x", "steps"), WorkLimitError);
    CHECK_THROWS_WITH(StepDoubling(100, 1 << 17, 1 << 20).give_up("x", "steps"), "x within 102400 steps");
  }
  SECTION("the error is never below the floor and NaN is never accepted") {
    StepDoubling fresh(8, 1 << 17, 16);
    CHECK(*fresh.judge(16, 0.0, 1e-6, 1e-14) == 1e-14);
    CHECK_FALSE(fresh.judge(32, std::nan(""), 1e-6));
  }
}

TEST_CASE("LTP kernels: a monodromy ladder stops at its work limit, and a limit it fits in changes nothing",
          "[ltp][mathieu]") {
  // Damped Mathieu inside the first tongue at a = 1, q = 0.2, c = 0.01 (no time reversal: the whole
  // period at every level): the ladder from 8 steps converges at some N, having taken 8 + 16 + … + N
  // = 2N − 8 steps. Exactly that work gives the same multipliers; one flop less cannot take level N,
  // and the ladder stops as a WorkLimitError.
  const LinearPeriodicSystem sys = mathieu(1.0, 0.2, 0.01);
  FloquetOptions options{FloquetMethod::monodromy, 0, 1e-10, false, {}};
  const FloquetResult free = floquet_multipliers(sys, options);
  REQUIRE(free.steps > 16);
  options.max_flops = (2.0 * free.steps - 8) * monodromy_step_work(sys);
  const FloquetResult fitted = floquet_multipliers(sys, options);
  CHECK(fitted.steps == free.steps);
  CHECK((fitted.multipliers - free.multipliers).cwiseAbs().maxCoeff() == 0);
  options.max_flops = std::nextafter(options.max_flops, 0.0);
  CHECK_THROWS_AS(floquet_multipliers(sys, options), WorkLimitError);
  CHECK_THROWS_WITH(floquet_multipliers(sys, options), Catch::Contains("all that the work limit affords"));
}

TEST_CASE("LTP kernels: a half-period ladder that goes on over the whole period counts its steps as whole",
          "[ltp][mathieu]") {
  // Undamped, the same point: the half-period levels 8 … S (S the safe count; half a step's work
  // each, 2S − 8 steps) do not settle to 1e-10, and the ladder goes on over the whole period: S
  // again, then 2S … N, 2N − S whole steps at twice the work. Exactly that work gives the same
  // multipliers; one flop less stops it, as does the work the levels would take if all were halved.
  const LinearPeriodicSystem sys = mathieu(1.0, 0.2);
  REQUIRE(reversing_signature(sys));
  FloquetOptions options{FloquetMethod::monodromy, 0, 1e-10, false, {}};
  const FloquetResult free = floquet_multipliers(sys, options);
  const int safe = minimum_magnus_steps(sys);
  REQUIRE(safe >= 8);
  REQUIRE(free.steps > safe);  // past the safe count: over the whole period
  const double half = monodromy_step_work(sys), whole = magnus_step_work(sys.state_size());
  REQUIRE(whole == 2 * half);
  options.max_flops = (2.0 * safe - 8) * half + (2.0 * free.steps - safe) * whole;
  const FloquetResult fitted = floquet_multipliers(sys, options);
  CHECK(fitted.steps == free.steps);
  CHECK((fitted.multipliers - free.multipliers).cwiseAbs().maxCoeff() == 0);
  options.max_flops = std::nextafter(options.max_flops, 0.0);
  CHECK_THROWS_AS(floquet_multipliers(sys, options), WorkLimitError);
  options.max_flops = (2.0 * free.steps - 8) * half;
  CHECK_THROWS_AS(floquet_multipliers(sys, options), WorkLimitError);
}

namespace {

// Two modes as the blade's axial and bending ones: the coefficient loads the first (G₁₁ = 1), the
// gyroscopic term joins the two, and `cross` couples them in G as the blade's fields never do.
LinearPeriodicSystem gyroscopic_pair(double damping, std::complex<double> f1, double cross = 0) {
  Eigen::MatrixXd G(2, 2), C(2, 2);
  G << 1, cross, cross, 0;
  C << damping, 0.4, -0.4, damping;
  return modal_periodic_system({Eigen::Vector2d(1.0, 2.3), G, C}, {0.1, f1}, 2.0, damping == 0);
}

}  // namespace

TEST_CASE("LTP kernels: an undamped gyroscopic pair under an even coefficient reverses in time, not with damping, an odd "
          "part of f or a coupling within one class do not",
          "[ltp]") {
  const LinearPeriodicSystem even = gyroscopic_pair(0, 0.3);
  const std::optional<Eigen::VectorXd> r = reversing_signature(even);
  REQUIRE(r);
  const Eigen::MatrixXd R = r->asDiagonal();
  CHECK((R * even.A0 * R + even.A0).isZero(0));
  CHECK((R * even.B * R + even.B).isZero(0));
  CHECK_FALSE(reversing_signature(gyroscopic_pair(0.01, 0.3)));
  CHECK_FALSE(reversing_signature(gyroscopic_pair(0, {0.3, 0.1})));
  CHECK_FALSE(reversing_signature(gyroscopic_pair(0, 0.3, 0.2)));
}

TEST_CASE("LTP kernels: the half-period monodromy R U⁻¹ R U is the whole period's, by RKF45 at rtol 1e-12", "[ltp]") {
  // The stable and the unstable side of the pair's first tongue, and one where U is too ill
  // conditioned for U⁻¹ (a growth of e^40 per half period), which integrates the second half too.
  for (const double f1 : {0.3, 1.2, 30.0}) {
    const LinearPeriodicSystem sys = gyroscopic_pair(0, f1);
    REQUIRE(reversing_signature(sys));
    const Eigen::VectorXcd half = monodromy_multipliers(sys, 2048);
    const Eigen::VectorXcd whole = sorted_eigenvalues(rkf45_monodromy(sys, 1e-12));
    INFO("f1 = " << f1 << ", max|rho| = " << std::abs(whole(0)));
    CHECK(multiplier_set_distance(half, whole) <= 1e-8 * std::max(1.0, std::abs(whole(0))));
  }
}
