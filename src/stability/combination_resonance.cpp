#include "bladestab/stability/combination_resonance.hpp"

#include <cmath>

#include "bladestab/base/constants.hpp"

namespace bladestab {

// The largest |δ|/θ named: on the paper blade's maps the combinations that fill the islands sit
// within 0.09 θ; those beyond 0.2 θ came from single points near the F̄ window's top.
constexpr double max_detuning = 0.1;

std::optional<Combination> nearest_combination(const Eigen::VectorXd& omega, double theta, std::complex<double> rho,
                                               int max_order, double phase_tolerance) {
  const double period = two_pi / theta;
  const auto wrapped = [](double phase) { return std::remainder(phase, two_pi); };  // in [−π, π]
  const double phase = std::abs(std::arg(rho));
  std::optional<Combination> best;
  for (Eigen::Index i = 0; i < omega.size(); ++i) {
    for (Eigen::Index j = i + 1; j < omega.size(); ++j) {
      for (int n = 1; n <= max_order; ++n) {
        for (const bool sum : {true, false}) {
          const double delta = (sum ? omega(i) + omega(j) : omega(j) - omega(i)) - n * theta;
          if (std::abs(delta) > max_detuning * theta) continue;
          // The locked pair's exponent (header): its phase over a period, compared up to sign.
          const double predicted = std::abs(wrapped((sum ? omega(i) - delta / 2 : omega(i) + delta / 2) * period));
          if (std::abs(predicted - phase) > phase_tolerance) continue;
          // The lowest order first (a tongue of order n opens like F̄ⁿ), then the least detuning.
          if (!best || n < best->order || (n == best->order && std::abs(delta / theta) < std::abs(best->detuning))) {
            best = Combination{static_cast<int>(i) + 1, static_cast<int>(j) + 1, sum, n, delta / theta};
          }
        }
      }
    }
  }
  return best;
}

}  // namespace bladestab
