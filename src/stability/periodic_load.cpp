#include "bladestab/stability/periodic_load.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"

namespace bladestab {
namespace {

using cplx = std::complex<double>;

// φ1(z) = (e^z − 1)/z and ψ(z) = ∫₀¹ u e^{zu} du = (e^z (z − 1) + 1)/z², by series near 0.
cplx phi1(cplx z) {
  if (std::abs(z) < 1e-2) {
    cplx sum = 0, term = 1;
    for (int k = 0; k < 12; ++k) {
      sum += term / static_cast<double>(k + 1);
      term *= z / static_cast<double>(k + 1);
    }
    return sum;
  }
  return (std::exp(z) - 1.0) / z;
}

cplx psi(cplx z) {
  if (std::abs(z) < 1e-2) {
    cplx sum = 0, term = 1;  // Σ z^k / (k! (k + 2))
    for (int k = 0; k < 12; ++k) {
      sum += term / static_cast<double>(k + 2);
      term *= z / static_cast<double>(k + 1);
    }
    return sum;
  }
  return (std::exp(z) * (z - 1.0) + 1.0) / (z * z);
}

// ∫₀^c e^{sτ} dτ and ∫₀^c τ e^{sτ} dτ.
cplx integral_exp(cplx s, double c) { return c * phi1(s * c); }
cplx integral_t_exp(cplx s, double c) { return c * c * psi(s * c); }

}  // namespace

double PulseTrain::angular_frequency() const { return 2 * pi / period_s; }

// The time since the current pulse started, if one is on at t.
std::optional<double> PulseTrain::time_in_pulse(double t) const {
  if (t < 0) return std::nullopt;
  const double p = std::floor(t / period_s);
  if (count > 0 && p >= count) return std::nullopt;
  // Not below 0: t − p·period rounds to −1e-18 s at some pulse starts where t/period rounds up to p
  // (sample 600 of 200 a revolution), and a half-sine there pulled the tip (+1.7e-8 N).
  const double tau = std::max(0.0, t - p * period_s);
  // Half-open window [0, t_c): at a pulse's end the force is already off, so an integrator step
  // that lands there starts the next step with the right-hand limit.
  if (tau >= contact_time_s && contact_time_s < period_s) return std::nullopt;
  return tau;
}

double PulseTrain::force(double t) const {
  const std::optional<double> tau = time_in_pulse(t);
  if (!tau) return 0;
  const double c = contact_time_s, F = peak_n, x = *tau;
  switch (profile) {  // Appendix A, docs/theory.md §3.2
    case PulseProfile::half_sine: return -F * std::sin(pi * x / c);                    // (38)
    case PulseProfile::cosine: return -F / 2 + F / 2 * std::cos(2 * pi * x / c);      // (A.2)
    case PulseProfile::triangular: return -F * 2 * std::min(x, c - x) / c;            // (A.3)
    case PulseProfile::sawtooth: return -F * x / c;                                   // (A.4)
    case PulseProfile::rectangular: return -F;                                        // (A.6)
    case PulseProfile::impulse: return -F;  // a short rectangle; the impulse is F_max t_c
  }
  return 0;
}

double PulseTrain::force_rate(double t) const {
  const std::optional<double> tau = time_in_pulse(t);
  if (!tau) return 0;
  const double c = contact_time_s, F = peak_n, x = *tau;
  switch (profile) {  // the derivatives of force(t)
    case PulseProfile::half_sine: return -F * pi / c * std::cos(pi * x / c);
    case PulseProfile::cosine: return -F * pi / c * std::sin(2 * pi * x / c);
    case PulseProfile::triangular: return (x < c / 2 ? -2 : 2) * F / c;
    case PulseProfile::sawtooth: return -F / c;
    case PulseProfile::rectangular:
    case PulseProfile::impulse: return 0;
  }
  return 0;
}

double PulseTrain::max_force_rate() const {
  switch (profile) {  // force_rate's largest magnitude: at the edges, the quarter pulse, or constant
    case PulseProfile::half_sine:
    case PulseProfile::cosine: return peak_n * pi / contact_time_s;
    case PulseProfile::triangular: return 2 * peak_n / contact_time_s;
    case PulseProfile::sawtooth: return peak_n / contact_time_s;
    case PulseProfile::rectangular:
    case PulseProfile::impulse: return 0;
  }
  return 0;
}

std::vector<double> PulseTrain::edges(double t0, double t1) const {
  std::vector<double> out;
  for (long p = std::max(0L, static_cast<long>(std::floor(t0 / period_s))); p * period_s <= t1; ++p) {
    if (count > 0 && p >= count) break;
    for (double e : {p * period_s, p * period_s + contact_time_s}) {
      if (e >= t0 && e <= t1) out.push_back(e);
    }
  }
  return out;
}

cplx PulseTrain::fourier_coefficient(int m) const {
  const double c = contact_time_s, F = peak_n, T = period_s;
  const cplx s(0, -m * angular_frequency());  // e^{sτ} = e^{−imθτ}
  const cplx i(0, 1);
  cplx integral = 0;  // ∫₀^c F(τ) e^{sτ} dτ
  switch (profile) {
    case PulseProfile::half_sine: {  // sin(aτ) = (e^{iaτ} − e^{−iaτ})/(2i)
      const double a = pi / c;
      integral = -F / (2.0 * i) * (integral_exp(s + i * a, c) - integral_exp(s - i * a, c));
      break;
    }
    case PulseProfile::cosine: {
      const double b = 2 * pi / c;
      integral = -F / 2 * integral_exp(s, c) + F / 4 * (integral_exp(s + i * b, c) + integral_exp(s - i * b, c));
      break;
    }
    case PulseProfile::triangular: {  // rising on [0, c/2]; falling part mirrored: τ' = c − τ
      const double h = c / 2;
      integral = -2 * F / c * (integral_t_exp(s, h) + std::exp(s * c) * integral_t_exp(-s, h));
      break;
    }
    case PulseProfile::sawtooth: integral = -F / c * integral_t_exp(s, c); break;
    case PulseProfile::rectangular: integral = -F * integral_exp(s, c); break;
    case PulseProfile::impulse: integral = -F * c; break;  // δ of weight F_max t_c
  }
  return integral / T;
}

double PulseTrain::mean_square() const {
  const double r = contact_time_s / period_s, F2 = peak_n * peak_n;
  switch (profile) {
    case PulseProfile::half_sine: return F2 * r / 2;
    case PulseProfile::cosine: return F2 * r * 3 / 8;
    case PulseProfile::triangular:
    case PulseProfile::sawtooth: return F2 * r / 3;
    case PulseProfile::rectangular: return F2 * r;
    case PulseProfile::impulse: return HUGE_VAL;
  }
  return 0;
}

PulseTrain pulse_train(const Scene& scene) {
  const LoadSpec& l = scene.load;
  const double speed = scene.operation.speed_rad_s;
  PulseTrain t;
  t.profile = l.profile;
  t.peak_n = l.fmax_over_fcr * BladeProperties(scene.blade).critical_load();
  t.count = l.pulse_count;
  if (l.pulse_frequency_hz) {
    t.period_s = 1 / *l.pulse_frequency_hz;
  } else if (speed > 0) {
    t.period_s = 2 * pi / (l.pulses_per_rev * speed);
  } else {
    t.period_s = 1;
    t.frequency_known = false;
  }
  // t̄_c is a fraction of a revolution; without rotation, a fraction of the pulse period.
  const double revolution = speed > 0 ? 2 * pi / speed : t.period_s * l.pulses_per_rev;
  t.contact_time_s = l.contact_time_rev * revolution;
  if (t.contact_time_s > t.period_s * (1 + 1e-12)) {
    throw InputError(fmt::format("load.contact_time_rev = {}: the contact ({:.6g} s) outlasts the pulse period "
                                 "({:.6g} s)", l.contact_time_rev, t.contact_time_s, t.period_s));
  }
  return t;
}

LoadSeries cosine_approximation(const PulseTrain& train) {
  LoadSeries series;
  series.angular_frequency = train.angular_frequency();
  series.frequency_known = train.frequency_known;
  series.coefficients = {cplx(-train.peak_n / 2, 0), cplx(train.peak_n / 4, 0)};
  series.cosine_approximation = true;
  return series;
}

LoadSeries fourier_series(const PulseTrain& train, double relative_tail, int max_harmonics) {
  if (train.profile == PulseProfile::impulse) {
    throw InputError("load.profile = \"impulse\" with load.approximation = \"fourier\": an impulse train has no "
                     "convergent Fourier series; use another profile or the time domain");
  }
  LoadSeries series;
  series.angular_frequency = train.angular_frequency();
  series.frequency_known = train.frequency_known;
  const double total = train.mean_square();
  double captured = std::norm(train.fourier_coefficient(0));
  series.coefficients.push_back(train.fourier_coefficient(0));
  for (int m = 1; m <= max_harmonics; ++m) {
    const cplx Fm = train.fourier_coefficient(m);
    series.coefficients.push_back(Fm);
    captured += 2 * std::norm(Fm);  // F_m and F_{−m}
    series.relative_tail = total > 0 ? std::sqrt(std::max(0.0, total - captured) / total) : 0;
    if (series.relative_tail <= relative_tail) break;
  }
  return series;
}

PeriodicPulse periodic_pulse(const PulseTrain& train) {
  PeriodicPulse pulse{train.period_s, train.contact_time_s, [train](double t) { return train.force(t); }, {}};
  if (train.profile == PulseProfile::impulse) pulse.impulse = -train.peak_n * train.contact_time_s;
  return pulse;
}

double LoadSeries::value(double t) const { return fourier_sum(coefficients, angular_frequency, t); }

double LoadSeries::minimum() const {
  if (exact_pulse) return -exact_peak_n;
  const int samples = 64 * std::max(1, harmonics());
  const double period = 2 * pi / angular_frequency;
  double least = 0;
  for (int k = 0; k < samples; ++k) least = std::min(least, value(period * k / samples));
  return least;
}

LoadSeries exact_pulse_mean(const PulseTrain& train) {
  LoadSeries series;
  series.angular_frequency = train.angular_frequency();
  series.frequency_known = train.frequency_known;
  series.coefficients = {train.fourier_coefficient(0)};
  series.exact_pulse = true;
  series.exact_peak_n = train.peak_n;
  return series;
}

LoadSeries load_series(const Scene& scene, double relative_tail, int max_harmonics) {
  const PulseTrain train = pulse_train(scene);
  switch (scene.load.approximation) {
    case LoadApproximation::cosine: return cosine_approximation(train);
    case LoadApproximation::fourier: return fourier_series(train, relative_tail, max_harmonics);
    case LoadApproximation::exact: return exact_pulse_mean(train);
  }
  return {};
}

void refuse_impulse_jump(const Scene& scene) {
  if (scene.load.profile != PulseProfile::impulse || scene.load.approximation != LoadApproximation::exact) return;
  throw InputError("load.profile = \"impulse\" with load.approximation = \"exact\": the velocity jump has no "
                   "continuum limit (on the paper blade its max|ρ| grows with the terms: 1.07 at 16, 1.92 at 36, 23 "
                   "at 200); use load.profile = \"rectangular\" with a short load.contact_time_rev");
}

}  // namespace bladestab
