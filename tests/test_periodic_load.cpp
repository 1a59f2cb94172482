// Pulse trains (Appendix A): closed-form Fourier coefficients against direct quadrature of the
// pulse, Parseval, and the cosine approximation (42).
#include <catch2/catch.hpp>

#include <cmath>

#include "bladestab/periodic_load.hpp"
#include "quadrature.hpp"
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

TEST_CASE("the cosine approximation is -F/2 + F/2 cos(theta t)", "[load]") {
  const PulseTrain p = pulse_train(testing_support::paper_scene());
  const LoadSeries c = cosine_approximation(p);
  REQUIRE(c.harmonics() == 1);
  CHECK(c.coefficients[0] == std::complex<double>(-p.peak_n / 2, 0));
  CHECK(c.coefficients[1] == std::complex<double>(p.peak_n / 4, 0));
  CHECK(p.peak_n == Approx(5 * 64637.0).epsilon(1e-4));
}
