#pragma once
// What a transient response says: amplitude spectra (Hann-windowed FFT), dominant frequencies
// with sub-bin interpolation, and the growth of the envelope per revolution.
#include <vector>

namespace bladestab {

struct Spectrum {
  std::vector<double> frequency_hz;
  std::vector<double> amplitude;  // one-sided, in the signal's unit; a pure sine of amplitude a shows ≈ a
};

// Mean removed, Hann window, amplitude corrected for the window's coherent gain.
Spectrum amplitude_spectrum(const std::vector<double>& signal, double sample_rate_hz);

// The largest peak at or above `min_hz`, refined by a parabola through log amplitudes of the three
// bins around it (exact for a Gaussian peak; the Hann main lobe is close to one).
double dominant_frequency(const Spectrum& spectrum, double min_hz = 0);

// Envelope growth per revolution: exp of the least-squares slope of ln(peak |x| per revolution)
// over the whole revolutions from `first_revolution` on; 1 for a steady response. For a signal
// about zero (the lateral tip deflection); a multiplier ρ > 0 grows with an offset that a mean
// subtraction would distort.
double growth_per_revolution(const std::vector<double>& revolutions, const std::vector<double>& signal,
                             int first_revolution);

}  // namespace bladestab
