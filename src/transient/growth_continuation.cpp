#include <cmath>

#include "transient_parts.hpp"

namespace bladestab::detail {
namespace {

// One revolution's map of a change (docs/theory.md §5.7): the homogeneous part of its propagators,
// a change's last entry (the augmentation's constant) being 0. Column by column through the
// landings the map needs: the pulse edges and every landing inside a contact (its pieces are
// cached), the free flight between them one exponential each.
Eigen::MatrixXd revolution_map(ExactStepper& stepper, const std::vector<Landing>& revolution, double start) {
  std::vector<double> kept;
  double previous = start;
  for (std::size_t k = 0; k < revolution.size(); ++k) {
    const double t = revolution[k].t;
    const bool contact = stepper.pulses().time_in_pulse(0.5 * (previous + t)).has_value();
    if (revolution[k].edge || contact || k + 1 == revolution.size()) kept.push_back(t);
    previous = t;
  }
  const Eigen::Index size = 2 * stepper.modes();
  Eigen::MatrixXd map(size, size);
  double ignored_work = 0;
  for (Eigen::Index j = 0; j < size; ++j) {
    Eigen::VectorXd z = Eigen::VectorXd::Unit(size + 1, j);
    double t = start;
    for (const double next : kept) {
      stepper.step(t, next, z, ignored_work);
      t = next;
    }
    map.col(j) = z.head(size);
  }
  return map;
}

}  // namespace

std::vector<double> continue_change(ExactStepper& stepper, const Eigen::VectorXd& change, const std::vector<Landing>& revolution,
                             double start) {
  const Eigen::MatrixXd map = revolution_map(stepper, revolution, start);
  std::vector<double> log_norms;
  Eigen::VectorXd d = change.head(map.rows()), next(map.rows());
  // Each revolution from a unit change; the logarithms of the norms add up (½|y|² is the energy in
  // these coordinates).
  double log_scale = std::log(d.norm() / std::sqrt(2.0));
  d.normalize();
  for (int k = 0; k < growth_continuation; ++k) {
    next.noalias() = map * d;
    const double norm = next.norm();
    if (!(norm > 0 && std::isfinite(norm))) break;
    d = next / norm;
    log_scale += std::log(norm);
    log_norms.push_back(log_scale);
  }
  return log_norms;
}

bool revolutions_repeat(const PulseTrain& pulses, double revolution, int whole) {
  if (pulses.count > 0) {
    const double last_pulse_end = (pulses.count - 1) * pulses.period_s + std::min(pulses.contact_time_s, pulses.period_s);
    return (whole - 1) * revolution >= last_pulse_end;
  }
  const double periods = revolution / pulses.period_s;
  return std::round(periods) >= 1 && std::abs(periods - std::round(periods)) <= 1e-9 * periods;
}

}  // namespace bladestab::detail
