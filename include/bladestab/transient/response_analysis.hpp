#pragma once
// What a transient response says: amplitude spectra (Hann-windowed FFT), dominant frequencies
// with sub-bin interpolation, and the growth of the envelope per revolution.
#include <optional>
#include <string>
#include <vector>

namespace bladestab {

struct Spectrum {
  std::vector<double> frequency_hz;
  std::vector<double> amplitude;  // one-sided, in the signal's unit; a pure sine of amplitude a shows ≈ a
  double rounding = 0;            // the amplitude the samples' own rounding can make: 64 ε of the largest |sample|
};

// Mean removed, Hann window, amplitude corrected for the window's coherent gain.
Spectrum amplitude_spectrum(const std::vector<double>& signal, double sample_rate_hz);

// The largest peak at or above `min_hz`, refined by a parabola through log amplitudes of the three
// bins around it (exact for a Gaussian peak; the Hann main lobe is close to one); none where there
// is no bin or every amplitude is zero (a motion the load does not excite).
std::optional<double> dominant_frequency(const Spectrum& spectrum, double min_hz = 0);

// Growth per revolution of a sequence a_k > 0, one value per revolution that grows like max|ρ|^k
// (for a transient: the change of the state over revolution k, see TransientResult): exp of the
// least-squares slope of ln a_k over the second half of the sequence, where the decaying multipliers
// have faded. Meaningful only with at least `min_revolutions` values and a fit that pins the slope
// down to `max_standard_error` (the standard error of ln growth, from the fit's residual);
// otherwise `omitted` says why.
struct GrowthFit {
  double growth = 1;          // per revolution
  double standard_error = 0;  // of ln growth
  double largest_residual = 0;  // of ln a_k about the fitted line, over the fitted half
  double error_estimate = 0;  // of growth, absolute: what the fit leaves open (see fit_growth)
  std::string omitted;        // empty: meaningful
};
// error_estimate: twice the standard error, as growth·(e^{2σ} − 1), or where larger the largest
// distance of a single revolution's ratio a_k/a_{k−1} in the fitted half from the growth.
GrowthFit fit_growth(const std::vector<double>& per_revolution, int min_revolutions = 6,
                     double max_standard_error = 1e-2);

// The same fit of ln a_k given as the logarithms y_k = ln a_k (a continuation of thousands of
// revolutions spans more than the range of doubles).
GrowthFit fit_log_growth(const std::vector<double>& log_per_revolution, int min_revolutions = 6,
                         double max_standard_error = 1e-2);

// The growth of a long continuation (growth_continuation.cpp: thousands of revolutions of a
// revolution's map) from the logarithms of its changes: fit_log_growth's slope. A beat of multipliers
// of one modulus keeps ln a_k within a band about a line, its residuals correlated, so the slope's
// standard error understates it: its estimate is the larger of twice that and 3R/m (the most a
// least-squares slope over m points can move for residuals bounded by R), plus how far the fitted
// growth moved from the continuation's first half to the whole; not the single revolutions' spread,
// which the beat keeps at its own size however long the continuation while the slope averages it out.
GrowthFit fit_continued_growth(const std::vector<double>& log_per_revolution);

// The relative rounding of a growth per revolution (or a multiplier) taken in doubles through a
// revolution's propagators, as a floor of its stated error: the free flight's exponential over
// most of a revolution scales and squares its stiff modes (‖A‖₁T ~ 1e4), and the continuation and
// the monodromy's eigenvalue, each converged in its own steps, differ by up to 3.4e-11 (9 terms,
// rectangular train: tests/test_fast_transient.cpp).
inline constexpr double growth_rounding = 1e-10;

// The growth of a run cut short (the response left the model): the last ratio a_K/a_{K−1}, which
// converges to max|ρ| as the other multipliers' share fades like (|ρ₂|/max|ρ|)^K; error_estimate
// the change from the ratio before, |a_K/a_{K−1} − a_{K−1}/a_{K−2}| (a geometric convergence
// moves less than that from here on). Meaningful with at least 3 values.
GrowthFit latest_growth(const std::vector<double>& per_revolution);

}  // namespace bladestab
