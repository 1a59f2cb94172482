// Pulse trains (Appendix A): closed-form Fourier coefficients against direct quadrature of the
// pulse, Parseval, the cosine approximation (42) in time and as the periodic system carries it.
#include <catch2/catch.hpp>

#include <boost/math/quadrature/gauss.hpp>
#include <cmath>

#include "bladestab/base/constants.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "blade/quadrature.hpp"
#include "support/scenes.hpp"

using namespace bladestab;

namespace {
// (1/T) ∫ F(t) e^{−imθt} dt by Gauss–Legendre on each smooth piece of the pulse.
std::complex<double> quadrature_coefficient(const PulseTrain& p, int m) {
  std::complex<double> sum = 0;
  const double c = p.contact_time_s;
  for (auto [a, b] : {std::pair{0.0, c / 2}, std::pair{c / 2, c}}) {  // the triangle's kink at c/2
    const QuadratureRule rule = gauss_legendre(200, a, b);
    for (Eigen::Index q = 0; q < rule.points.size(); ++q) {
      const double t = rule.points(q);
      sum += rule.weights(q) * p.force(t) * std::exp(std::complex<double>(0, -m * p.angular_frequency() * t));
    }
  }
  return sum / p.period_s;
}
}  // namespace

TEST_CASE("exact Fourier coefficients of every pulse profile match quadrature of the pulse", "[load]") {
  for (const char* profile : {"half-sine", "cosine", "triangular", "saw-tooth", "rectangular"}) {
    for (double tc : {0.01, 0.3}) {
      const Scene s = testing_support::paper_scene({std::string("load.profile=") + profile,
                                                    "load.contact_time_rev=" + std::to_string(tc)});
      const PulseTrain p = pulse_train(s);
      CHECK(p.period_s == Approx(2 * 3.14159265358979323846 / 300).epsilon(1e-15));
      for (int m : {0, 1, 2, 7, 40, 99, 100, 101, 250}) {
        INFO(profile << ", t̄c = " << tc << ", m = " << m);
        const std::complex<double> exact = p.fourier_coefficient(m), numeric = quadrature_coefficient(p, m);
        CHECK(std::abs(exact - numeric) < 1e-12 * p.peak_n);
      }
    }
  }
}

TEST_CASE("Fourier series truncation reports its Parseval tail and converges", "[load]") {
  const Scene s = testing_support::paper_scene({"load.approximation=fourier", "load.contact_time_rev=0.2"});
  const PulseTrain p = pulse_train(s);
  const LoadSeries coarse = fourier_series(p, 1e-2, 500), fine = fourier_series(p, 1e-4, 5000);
  CHECK(coarse.relative_tail <= 1e-2);
  CHECK(fine.relative_tail <= 1e-4);
  CHECK(fine.harmonics() > coarse.harmonics());
  // The series reproduces the pulse: at the pulse's peak, to about its tail.
  double f = fine.coefficients[0].real();
  const double t = p.contact_time_s / 2, theta = p.angular_frequency();
  for (int m = 1; m <= fine.harmonics(); ++m) f += 2 * std::real(fine.coefficients[m] * std::exp(std::complex<double>(0, m * theta * t)));
  CHECK(f == Approx(-p.peak_n).epsilon(1e-3));
}

TEST_CASE("the cosine approximation (42) keeps the pulse train's peak-to-peak and frequency but not its t_c", "[load]") {
  // Sinha (42): F(t) ≈ −F_max/2 + (F_max/2) cos(2π f_p t), with "same peak-to-peak amplitude and
  // frequency" as the true train (38), disregarding t_c "by inherently assuming that t_c = 2π/Ω":
  // the cosine pulse (A.2) stretched over the whole period. Checked on samples in time against the
  // half-sine train it replaces and against that stretched cosine pulse.
  const PulseTrain train = pulse_train(testing_support::paper_scene());  // half-sine, F̄ = 5, t̄c = 0.01
  const PulseTrain stretched = pulse_train(
      testing_support::paper_scene({"load.profile=cosine", "load.contact_time_rev=1"}));
  const LoadSeries cosine = cosine_approximation(train);
  const double T = train.period_s, peak = 5 * 64637.0;  // F_cr = π²EI/(4L²) (docs/theory.md §8)
  REQUIRE(train.peak_n == Approx(peak).epsilon(1e-4));
  const int samples = 2000;  // per period; sample 1000 is T/2
  double train_low = 0, train_high = -1e300, low = 1e300, high = -1e300, mean = 0, worst = 0, aperiodic = 0;
  for (int i = 0; i <= samples; ++i) {
    const double t = T * i / samples, weight = (i == 0 || i == samples ? 0.5 : 1.0) / samples;  // trapezoid
    const double approximation = cosine.value(t), pulse = train.force(t);
    train_low = std::min(train_low, pulse), train_high = std::max(train_high, pulse);
    low = std::min(low, approximation), high = std::max(high, approximation);
    mean += weight * approximation;
    // (42) itself, and the cosine pulse (A.2) with t_c = T_p.
    worst = std::max(worst, std::abs(approximation - (-train.peak_n / 2 + train.peak_n / 2 * std::cos(two_pi * t / T))));
    worst = std::max(worst, std::abs(approximation - stretched.force(t)));
    aperiodic = std::max(aperiodic, std::abs(cosine.value(t + T) - approximation));
  }
  train_low = std::min(train_low, train.force(train.contact_time_s / 2));  // the half-sine's peak
  CHECK(worst < 1e-9 * peak);      // measured 7e-16 of F_max
  CHECK(aperiodic < 1e-9 * peak);  // periodic with the train's period
  // Same peak-to-peak, between the same extremes 0 and −F_max.
  CHECK(high - low == Approx(train_high - train_low).epsilon(1e-12));
  CHECK(high == Approx(0).margin(1e-9 * peak));
  CHECK(low == Approx(-peak).epsilon(1e-4));
  // One oscillation a period: zero at the pulse's start (the train's edge), the full −F_max half a
  // period later, where the true train is long over.
  CHECK(cosine.value(0) == Approx(0).margin(1e-9 * peak));
  CHECK(cosine.value(T / 2) == Approx(-train.peak_n).epsilon(1e-12));
  CHECK(train.force(T / 2) == 0);
  // At the true pulse's centre the approximation has hardly begun: −F_max sin²(π t̄c / 2) = −2.5e-4 F_max.
  CHECK(cosine.value(train.contact_time_s / 2) / -train.peak_n == Approx(std::pow(std::sin(pi * 0.01 / 2), 2)).epsilon(1e-6));
  // Ignoring t_c changes what the blade is fed: the mean −F_max/2 against the half-sine's
  // −(2/π) t̄c F_max (∫ sin over a half period), 78 times less.
  const double train_mean =
      boost::math::quadrature::gauss<double, 20>::integrate([&](double t) { return train.force(t); }, 0.0,
                                                             train.contact_time_s) / T;
  CHECK(mean == Approx(-peak / 2).epsilon(1e-4));
  CHECK(train_mean == Approx(-2 / pi * 0.01 * train.peak_n).epsilon(1e-12));
}

TEST_CASE("the periodic system carries the cosine load as the stiffness K(Omega) + F(t) G", "[load]") {
  // The LTP system of the whole model (no reduction) in its scaled modal coordinates: A(t)'s lower
  // left block is −(Λ + F(t) Ĝ) D⁻¹ with D = diag(ω) (periodic_system.hpp), so S(t) = −A₂₁(t) D is
  // the modal stiffness, whose eigenvalues are those of K(Ω) + F(t) G with M, F(t) the load (42) at t.
  // Against the generalized eigenproblem of the model's matrices at the load computed here: a wrong
  // sign, factor or phase of the load would move the loaded mode 1 by order one (at t = T/2 the blade
  // is just past its buckling load 4.954 F_cr at this speed).
  const Scene scene = testing_support::paper_scene();
  const BladeModel model = assemble_model(scene);
  const PeriodicSystem system =
      periodic_system(model, scene, load_series(scene), ReductionSpec{ReductionKind::none, 0, 0});
  const int n = system.kept_modes;
  REQUIRE(n == model.layout.size());
  const double T = system.period(), peak = 5 * model.blade.critical_load();
  const Eigen::MatrixXd D = system.A0.topRightCorner(n, n);
  const Eigen::VectorXd unloaded = Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(
                                       model.stiffness(300), model.M, Eigen::EigenvaluesOnly).eigenvalues();
  double worst = 0;
  for (double t : {0.0, T / 8, T / 4, 0.3 * T, T / 2, 3 * T / 4}) {
    const Eigen::MatrixXd A = system.A0 + system.variation(t) * system.B;
    const Eigen::MatrixXd S = -A.bottomLeftCorner(n, n) * D;
    const double F = -peak / 2 + peak / 2 * std::cos(two_pi * t / T);  // (42)
    const Eigen::VectorXd ours = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (S + S.transpose()),
                                                                                 Eigen::EigenvaluesOnly).eigenvalues();
    const Eigen::VectorXd reference = Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(
                                          model.stiffness(300, F), model.M, Eigen::EigenvaluesOnly).eigenvalues();
    CHECK((S - S.transpose()).norm() < 1e-12 * S.norm());
    for (int k = 0; k < 6; ++k) {
      INFO("t = " << t / T << " T, F = " << F << " N, mode " << k + 1 << ": ω² " << ours(k) << " against "
                  << reference(k));
      // Relative to the unloaded ω₁² (the loaded one passes through 0): measured ≤ 3e-9.
      const double error = std::abs(ours(k) - reference(k)) / unloaded(0);
      CHECK(error < 1e-7);
      worst = std::max(worst, error);
    }
    if (t == T / 2) CHECK(reference(0) < 0);  // buckled at the peak of the load
  }
  WARN("modal stiffness eigenvalues against K + F(t) G: largest difference " << worst << " of ω1²");
}

TEST_CASE("the rub pushes, never pulls: no pulse force above 0 at the samples of 400 revolutions", "[load]") {
  // At a pulse's start t − p·period can round to −1e-18 s (sample 600 of 200 a revolution at
  // 300 rad/s): the half-sine gave +1.7e-8 N there, which the chart refuses as a pull.
  for (const char* profile : {"half-sine", "triangular", "saw-tooth", "cosine"}) {
    const PulseTrain train = pulse_train(testing_support::paper_scene({std::string("load.profile=") + profile}));
    const double dt = train.period_s / 200;
    double most = -1;
    for (int n = 0; n <= 80000; ++n) most = std::max(most, train.force(n * dt));
    INFO(profile);
    CHECK(most <= 0);
  }
}
