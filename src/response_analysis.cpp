#include "bladestab/response_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <stdexcept>

#include <unsupported/Eigen/FFT>

namespace bladestab {

Spectrum amplitude_spectrum(const std::vector<double>& signal, double rate) {
  const std::size_t n = signal.size();
  if (n < 4) throw std::invalid_argument("a spectrum needs at least 4 samples");
  const double mean = std::accumulate(signal.begin(), signal.end(), 0.0) / n;
  const double pi = 3.14159265358979323846;
  std::vector<double> windowed(n);
  double gain = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double w = 0.5 - 0.5 * std::cos(2 * pi * k / (n - 1));
    windowed[k] = w * (signal[k] - mean);
    gain += w;
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> bins;
  fft.fwd(bins, windowed);
  Spectrum s;
  for (std::size_t k = 0; k <= n / 2; ++k) {
    s.frequency_hz.push_back(k * rate / n);
    s.amplitude.push_back((k == 0 ? 1.0 : 2.0) * std::abs(bins[k]) / gain);
  }
  return s;
}

double dominant_frequency(const Spectrum& s, double min_hz) {
  std::size_t best = 0;
  for (std::size_t k = 1; k + 1 < s.amplitude.size(); ++k) {
    if (s.frequency_hz[k] >= min_hz && (best == 0 || s.amplitude[k] > s.amplitude[best])) best = k;
  }
  if (best == 0) return 0;
  const double a = std::log(std::max(s.amplitude[best - 1], 1e-300)), b = std::log(s.amplitude[best]),
               c = std::log(std::max(s.amplitude[best + 1], 1e-300));
  const double offset = (a - c) / (2 * (a - 2 * b + c));
  const double df = s.frequency_hz[1] - s.frequency_hz[0];
  return s.frequency_hz[best] + (std::isfinite(offset) ? std::clamp(offset, -0.5, 0.5) : 0.0) * df;
}

double growth_per_revolution(const std::vector<double>& revs, const std::vector<double>& x, int first) {
  std::vector<double> peak;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const int r = static_cast<int>(std::floor(revs[k]));
    if (r < first || revs[k] >= std::floor(revs.back())) continue;  // whole revolutions only
    if (static_cast<int>(peak.size()) <= r - first) peak.resize(r - first + 1, 0.0);
    peak[r - first] = std::max(peak[r - first], std::abs(x[k]));
  }
  if (peak.size() < 2) return 1;
  // Least squares of ln peak against the revolution number.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(peak.size());
  for (std::size_t i = 0; i < peak.size(); ++i) {
    const double y = std::log(std::max(peak[i], 1e-300));
    sx += i, sy += y, sxx += double(i) * i, sxy += i * y;
  }
  return std::exp((m * sxy - sx * sy) / (m * sxx - sx * sx));
}

}  // namespace bladestab
