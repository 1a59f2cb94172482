// load.pulses_per_rev = p > 1 (docs/theory.md §3: pulse period T_p = T/p, θ = pΩ) in the frequency domain's
// series (the cosine approximation and the true pulse's Fourier series) and in the transient,
// against references computed here: the revolution's Fourier coefficients of the SPEC's pulse train
// by Gauss–Kronrod quadrature, the monodromy over a whole revolution by Runge–Kutta–Fehlberg 7(8),
// and the tip history by Dormand–Prince 5(4).
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <boost/math/quadrature/gauss.hpp>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/transient/transient.hpp"
#include "reference/blade_transient.hpp"
#include "reference/odeint_monodromy.hpp"
#include "reference/pulse_profiles.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

constexpr double pi = 3.14159265358979323846;

// c_k = (1/T) ∫₀ᵀ F(t) e^{−ikΩt} dt over one revolution T = 2π/Ω of the SPEC's train, k = 0..k_max:
// 20-point Gauss–Legendre on each contact window (where F is smooth; F = 0 elsewhere), split so that
// e^{−ik_maxΩt} turns by at most 1 rad in a piece (exact to rounding for such entire integrands).
std::vector<std::complex<double>> revolution_harmonics(const reference::PulseTrainReference& train, double speed,
                                                       int k_max) {
  using Gauss = boost::math::quadrature::gauss<double, 20>;
  const double revolution = 2 * pi / speed;
  const int pieces = 1 + static_cast<int>(k_max * speed * train.contact);
  const double h = train.contact / pieces;
  std::vector<std::complex<double>> c(k_max + 1, 0.0);
  for (double start = 0; start < revolution * (1 - 1e-12); start += train.period) {
    for (int piece = 0; piece < pieces; ++piece) {
      const double mid = start + (piece + 0.5) * h;
      // Gauss's abscissae are the non-negative half of a symmetric rule on [−1, 1].
      for (std::size_t i = 0; i < Gauss::abscissa().size(); ++i) {
        for (const double side : {1.0, -1.0}) {
          if (i == 0 && side < 0 && Gauss::abscissa()[0] == 0) continue;
          const double t = mid + side * Gauss::abscissa()[i] * h / 2;
          const double weight = Gauss::weights()[i] * h / 2 * train.force(t) / revolution;
          for (int k = 0; k <= k_max; ++k) c[k] += weight * std::exp(std::complex<double>(0, -k * speed * t));
        }
      }
    }
  }
  return c;
}

double series_at(const std::vector<std::complex<double>>& c, double speed, double t) {
  double f = c[0].real();
  for (std::size_t k = 1; k < c.size(); ++k) f += 2 * std::real(c[k] * std::exp(std::complex<double>(0, k * speed * t)));
  return f;
}

}  // namespace

TEST_CASE("three pulses per revolution: the Fourier series lives on the pulse period, harmonics 3m of the revolution",
          "[periodic_load][pulses_per_rev]") {
  const int p = 3;
  const Scene s = paper_scene({"load.pulses_per_rev=3", "load.approximation=fourier", "load.contact_time_rev=0.05"});
  const double speed = s.operation.speed_rad_s;
  const LoadSeries series = load_series(s);
  CHECK(series.angular_frequency == Approx(p * speed).epsilon(1e-14));
  const int M = series.harmonics();
  REQUIRE(M >= 5);
  const std::vector<std::complex<double>> c = revolution_harmonics(reference::scene_pulses(s), speed, p * M + 2);
  const double scale = std::abs(c[0]);  // the mean load, −F_max (2/π) p t_c / T
  double off_multiples = 0, series_error = std::abs(series.coefficients[0] - c[0]);
  for (int k = 1; k <= p * M + 2; ++k) {
    if (k % p != 0) {
      off_multiples = std::max(off_multiples, std::abs(c[k]));  // the p pulses cancel these harmonics
    } else if (k / p <= M) {
      series_error = std::max(series_error, std::abs(series.coefficients[k / p] - c[k]));  // F_m = c_{pm}
    }
  }
  INFO(M << " harmonics of θ; mean load " << c[0] << " N; largest harmonic off the multiples of 3: " << off_multiples
         << " N; largest |F_m − c_3m|: " << series_error << " N");
  CHECK(std::abs(c[p]) > 0.5 * scale);  // the harmonics that remain are of the mean's size
  CHECK(off_multiples < 1e-13 * scale);  // measured 1.7e-15
  CHECK(series_error < 1e-13 * scale);   // measured 5.9e-15
  // The cosine approximation (42) at θ = pΩ too.
  const LoadSeries cosine = load_series(paper_scene({"load.pulses_per_rev=3"}));
  CHECK(cosine.angular_frequency == Approx(p * speed).epsilon(1e-14));
}

TEST_CASE("p = 2 and 3 pulses per revolution: Floquet per pulse period to the power p is the revolution's monodromy",
          "[stability][pulses_per_rev][long_under_sanitizers]") {
  // Six bending terms (Euler–Bernoulli, no axial field): ω_max ≈ 1e5 rad/s keeps the 7(8) reference quick.
  for (const int p : {2, 3}) {
    for (const char* approximation : {"cosine", "fourier"}) {
      const Scene s = paper_scene({"model.theory=euler-bernoulli", "model.axial=false", "model.terms=6",
                                   "load.pulses_per_rev=" + std::to_string(p), "load.contact_time_rev=0.05",
                                   std::string("load.approximation=") + approximation});
      const double speed = s.operation.speed_rad_s, revolution = 2 * pi / speed;
      const PeriodicSystem sys = periodic_system(assemble_model(s), s, load_series(s));
      REQUIRE(sys.period() == Approx(revolution / p).epsilon(1e-14));
      const FloquetResult per_pulse = floquet_multipliers(sys, {FloquetMethod::monodromy, 0, 1e-10});
      // The reference's load over a whole revolution, from the SPEC: the cosine approximation (42)
      // −F_max/2 + (F_max/2) cos pΩt, or the revolution harmonics of the true train (kept to the
      // library's truncation, harmonics p·m with m ≤ M: the others vanish).
      const reference::PulseTrainReference train = reference::scene_pulses(s);
      std::vector<std::complex<double>> c(p * (sys.coefficients.size() - 1) + 1, 0.0);
      if (std::string(approximation) == "cosine") {
        c[0] = -train.peak / 2;
        c[p] = train.peak / 4;
      } else {
        c = revolution_harmonics(train, speed, static_cast<int>(c.size()) - 1);
      }
      // A(t) = A₀ + (F(t) − F₀) B with F₀ the mean the library put into A₀.
      const double F0 = sys.coefficients[0].real();
      const Eigen::MatrixXd phi = reference::odeint_propagator(
          sys.A0, sys.B, [&](double t) { return series_at(c, speed, t) - F0; }, {}, revolution, 1e-12);
      const Eigen::VectorXcd per_revolution = Eigen::EigenSolver<Eigen::MatrixXd>(phi, false).eigenvalues();
      const double distance = multiplier_set_distance(per_pulse.multipliers.array().pow(p), per_revolution);
      INFO("p = " << p << ", " << approximation << " (" << sys.coefficients.size() - 1 << " harmonics of θ): max|ρ| per pulse "
                  << per_pulse.max_abs_multiplier << ", set distance " << distance);
      CHECK(distance < 1e-8 * std::max(1.0, std::pow(per_pulse.max_abs_multiplier, p)));
    }
  }
}

TEST_CASE("three pulses per revolution in the transient: the force at the SPEC's times, the response of the reference",
          "[transient][pulses_per_rev][long_under_sanitizers]") {
  const Scene s = paper_scene({"model.theory=euler-bernoulli", "model.terms=4", "load.pulses_per_rev=3"});
  const BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = 2;
  o.tolerance = 1e-9;
  o.samples_per_revolution = 600;  // 6 samples per contact of 0.01 revolution
  const TransientResult r = run_transient(m, s, o);
  const reference::PulseTrainReference train = reference::scene_pulses(s);
  std::vector<double> times, lateral, axial;
  int pulses = 0;
  double previous = 0;
  for (const TransientSample& x : r.samples) {
    INFO("t = " << x.time_s << " s (" << x.revolutions << " revolutions)");
    CHECK(x.axial_force_n == Approx(train.force(x.time_s)).margin(1e-9 * train.peak));
    if (x.axial_force_n != 0 && previous == 0) {  // a pulse starts: at a multiple of a third of a revolution
      ++pulses;
      CHECK(std::abs(x.revolutions * 3 - std::round(x.revolutions * 3)) <= 1.0 / 600 * 3 + 1e-12);
    }
    previous = x.axial_force_n;
    times.push_back(x.time_s);
    lateral.push_back(x.tip_lateral_m);
    axial.push_back(x.tip_axial_m);
  }
  CHECK(pulses == 6);
  const double W = s.operation.speed_rad_s;
  const reference::BladeLoadCase load{W, m.gyroscopic(W), [&](double t) { return train.force(t); },
                                      train.edges(times.back()), 0};
  const reference::TipHistory h = reference::odeint_tip_history(m, load, rotating_equilibrium(m, W), times);
  const double d_lateral = reference::relative_history_difference(h.lateral, lateral);
  const double d_axial = reference::relative_history_difference(h.axial, axial);
  INFO("lateral difference " << d_lateral << " of the peak, axial " << d_axial);
  CHECK(d_lateral < 1e-6);  // rtol 1e-9, grown 1e2–1e3 times over the run
  CHECK(d_axial < 1e-6);
}
