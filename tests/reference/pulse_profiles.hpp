#pragma once
// The tip load of docs/theory.md §3 written out from its table, apart from the library's PulseTrain: the
// pulse shapes F(τ) on 0 ≤ τ ≤ t_c (Appendix A) and a train of them, pulse k occupying
// [k T_p, k T_p + t_c) (half-open: the force is off at a pulse's end). Header-only; the impulse is
// taken as the short rectangle of height F_max and width t_c (impulse F_max t_c, docs/theory.md §3, (A.5)).
#include <cmath>
#include <vector>

#include "bladestab/scene/scene.hpp"

namespace reference {

// F(τ) of one pulse of peak F_max = `peak` and contact time `contact` (docs/theory.md §3 table).
inline double pulse_shape(bladestab::PulseProfile profile, double peak, double contact, double tau) {
  constexpr double pi = 3.14159265358979323846;
  using bladestab::PulseProfile;
  switch (profile) {
    case PulseProfile::half_sine: return -peak * std::sin(pi * tau / contact);                                // (38)
    case PulseProfile::cosine: return -peak / 2 + peak / 2 * std::cos(2 * pi * tau / contact);               // (A.2)
    case PulseProfile::triangular: return tau <= contact / 2 ? -peak * 2 * tau / contact                      // (A.3)
                                                             : -peak * 2 * (contact - tau) / contact;
    case PulseProfile::sawtooth: return -peak * tau / contact;                                               // (A.4)
    case PulseProfile::rectangular:                                                                          // (A.6)
    case PulseProfile::impulse: return -peak;                                                                // (A.5)
  }
  return 0;
}

// An endless (count = 0) or finite train of pulses every `period` seconds.
struct PulseTrainReference {
  bladestab::PulseProfile profile = bladestab::PulseProfile::half_sine;
  double peak = 0, contact = 0, period = 0;
  int count = 0;

  double force(double t) const {
    if (t < 0) return 0;
    const double k = std::floor(t / period);
    const double tau = t - k * period;
    if ((count > 0 && k >= count) || tau >= contact) return 0;
    return pulse_shape(profile, peak, contact, tau);
  }
  // Pulse starts and ends in [0, t_end]: where F jumps or kinks.
  std::vector<double> edges(double t_end) const {
    std::vector<double> out;
    for (int k = 0; k * period <= t_end && (count == 0 || k < count); ++k) {
      out.push_back(k * period);
      if (k * period + contact <= t_end) out.push_back(k * period + contact);
    }
    return out;
  }
};

// The train a scene describes (docs/theory.md §3): F_max = F̄_max π²EI/(4L²), T_p = 2π/(p Ω) for p pulses per
// revolution (or 1/load.pulse_frequency_hz), t_c = t̄_c · 2π/Ω.
inline PulseTrainReference scene_pulses(const bladestab::Scene& s) {
  constexpr double pi = 3.14159265358979323846;
  const double revolution = 2 * pi / s.operation.speed_rad_s;
  PulseTrainReference r;
  r.profile = s.load.profile;
  r.peak = s.load.fmax_over_fcr * pi * pi * s.blade.youngs_modulus * s.blade.inertia / (4 * s.blade.length * s.blade.length);
  r.period = s.load.pulse_frequency_hz ? 1 / *s.load.pulse_frequency_hz : revolution / s.load.pulses_per_rev;
  r.contact = s.load.contact_time_rev * revolution;
  r.count = s.load.pulse_count;
  return r;
}

}  // namespace reference
