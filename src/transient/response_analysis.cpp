#include "bladestab/transient/response_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>
#include <unsupported/Eigen/FFT>

#include "bladestab/base/constants.hpp"

namespace bladestab {

namespace {

// The least length ≥ n whose prime factors are 2, 3 and 5: kissfft's radix butterflies. A length
// with a large prime factor p costs n·p (a 405-revolution run's 81001 samples, a prime: 18 s).
std::size_t fast_fft_length(std::size_t n) {
  for (std::size_t m = n;; ++m) {
    std::size_t rest = m;
    for (std::size_t p : {2, 3, 5}) {
      while (rest % p == 0) rest /= p;
    }
    if (rest == 1) return m;
  }
}

}  // namespace

Spectrum amplitude_spectrum(const std::vector<double>& signal, double rate) {
  const std::size_t n = signal.size();
  if (n < 4) throw std::invalid_argument("a spectrum needs at least 4 samples");
  // About the first sample: a vibration far below the signal's mean (a feather touch about the
  // static stretch) keeps its digits, and a constant signal gives exact zeros.
  std::vector<double> deviation(n);
  for (std::size_t k = 0; k < n; ++k) deviation[k] = signal[k] - signal[0];
  const double mean = std::accumulate(deviation.begin(), deviation.end(), 0.0) / n;
  std::vector<double> windowed(n);
  double gain = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double w = 0.5 - 0.5 * std::cos(2 * pi * k / (n - 1));
    windowed[k] = w * (deviation[k] - mean);
    gain += w;
  }
  // Zero-padded to a fast length: the window's gain is the samples', and the bins, k·rate/m, are
  // finer than rate/n.
  const std::size_t m = fast_fft_length(n);
  windowed.resize(m, 0.0);
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> bins;
  fft.fwd(bins, windowed);
  Spectrum s;
  // Each sample carries the rounding of its own size (the static stretch about which a feather
  // touch's vibration moves): a peak not above 64 ε of the largest is noise.
  s.rounding = 64 * std::numeric_limits<double>::epsilon() *
               std::abs(*std::max_element(signal.begin(), signal.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }));
  for (std::size_t k = 0; k <= m / 2; ++k) {
    s.frequency_hz.push_back(k * rate / m);
    s.amplitude.push_back((k == 0 ? 1.0 : 2.0) * std::abs(bins[k]) / gain);
  }
  return s;
}

std::optional<double> dominant_frequency(const Spectrum& s, double min_hz) {
  std::size_t best = 0;
  for (std::size_t k = 1; k + 1 < s.amplitude.size(); ++k) {
    if (s.frequency_hz[k] >= min_hz && (best == 0 || s.amplitude[k] > s.amplitude[best])) best = k;
  }
  if (best == 0 || !(s.amplitude[best] > s.rounding)) return std::nullopt;
  const double a = std::log(std::max(s.amplitude[best - 1], 1e-300)), b = std::log(s.amplitude[best]),
               c = std::log(std::max(s.amplitude[best + 1], 1e-300));
  const double offset = (a - c) / (2 * (a - 2 * b + c));
  const double df = s.frequency_hz[1] - s.frequency_hz[0];
  return s.frequency_hz[best] + (std::isfinite(offset) ? std::clamp(offset, -0.5, 0.5) : 0.0) * df;
}

GrowthFit fit_growth(const std::vector<double>& a, int min_revolutions, double max_standard_error) {
  std::vector<double> logs;
  for (std::size_t k = a.size() / 2; k < a.size(); ++k) {
    if (!(a[k] > 0 && std::isfinite(a[k]))) {
      GrowthFit fit;
      fit.omitted = a.size() < static_cast<std::size_t>(min_revolutions)
                        ? fmt::format("{} whole revolutions; the fit needs {}", a.size(), min_revolutions)
                        : fmt::format("revolution {} changed the state by {}: nothing to fit", k + 1, a[k]);
      return fit;
    }
  }
  for (const double x : a) logs.push_back(x > 0 ? std::log(x) : 0.0);  // the first half: only counted
  return fit_log_growth(logs, min_revolutions, max_standard_error);
}

GrowthFit fit_log_growth(const std::vector<double>& y, int min_revolutions, double max_standard_error) {
  GrowthFit fit;
  const int count = static_cast<int>(y.size());
  if (count < min_revolutions) {
    fit.omitted = fmt::format("{} whole revolutions; the fit needs {}", count, min_revolutions);
    return fit;
  }
  const int first = count / 2, m = count - first;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = first; k < count; ++k) sx += k, sy += y[k], sxx += double(k) * k, sxy += k * y[k];
  // Least squares y = α + βk; the standard error of β from the residual with m − 2 degrees of freedom.
  const double Sxx = sxx - sx * sx / m, slope = (sxy - sx * sy / m) / Sxx, intercept = (sy - slope * sx) / m;
  double residual = 0;
  for (int k = first; k < count; ++k) {
    const double r = y[k] - intercept - slope * k;
    residual += r * r;
    fit.largest_residual = std::max(fit.largest_residual, std::abs(r));
  }
  fit.growth = std::exp(slope);
  fit.standard_error = std::sqrt(residual / (m - 2) / Sxx);
  // Also the spread of the single revolutions' ratios about the fit: a short run's decaying
  // multipliers bias the slope without scattering the points.
  fit.error_estimate = fit.growth * std::expm1(2 * fit.standard_error);
  for (int k = first + 1; k < count; ++k) fit.error_estimate = std::max(fit.error_estimate, std::abs(std::exp(y[k] - y[k - 1]) - fit.growth));
  if (!(fit.standard_error <= max_standard_error)) {
    fit.omitted = fmt::format("not a steady exponential: the fit over revolutions {} to {} leaves ln growth uncertain by {:.2g} "
                              "(allowed {:g}); run more revolutions",
                              first + 1, count, fit.standard_error, max_standard_error);
  }
  return fit;
}

GrowthFit fit_continued_growth(const std::vector<double>& y) {
  GrowthFit fit = fit_log_growth(y);
  if (!fit.omitted.empty()) return fit;
  const GrowthFit first_half = fit_log_growth({y.begin(), y.begin() + static_cast<std::ptrdiff_t>(y.size() / 2)});
  const double drift = first_half.omitted.empty() ? std::abs(fit.growth - first_half.growth) : 0.0;
  const double fitted = static_cast<double>(y.size() - y.size() / 2);
  const double slope_error = std::max(2 * fit.standard_error, 3 * fit.largest_residual / fitted);
  fit.error_estimate = fit.growth * std::expm1(slope_error) + drift;
  return fit;
}

GrowthFit latest_growth(const std::vector<double>& a) {
  GrowthFit fit;
  const std::size_t count = a.size();
  if (count < 3) {
    fit.omitted = fmt::format("{} whole revolutions before the stop; the growth needs 3", count);
    return fit;
  }
  const double last = a[count - 1] / a[count - 2], before = a[count - 2] / a[count - 3];
  if (!(std::isfinite(last) && std::isfinite(before) && last > 0 && before > 0)) {
    fit.omitted = fmt::format("the last revolutions changed the state by {}, {}, {}: nothing to fit", a[count - 3],
                              a[count - 2], a[count - 1]);
    return fit;
  }
  fit.growth = last;
  fit.error_estimate = std::abs(last - before);
  fit.standard_error = fit.error_estimate / last;
  return fit;
}

}  // namespace bladestab
