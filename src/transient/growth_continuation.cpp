#include <cmath>
#include <optional>

#include "bladestab/transient/response_analysis.hpp"
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

Continuation continue_change(ExactStepper& stepper, const Eigen::VectorXd& change, const std::vector<Landing>& revolution,
                             double start) {
  const Eigen::MatrixXd map = revolution_map(stepper, revolution, start);
  Continuation c;
  Eigen::VectorXd d = change.head(map.rows()), next(map.rows());
  // Each revolution from a unit change, its norm times the norm before (½|y|² is the energy in these
  // coordinates): the product ends the continuation where it leaves [1e-300, 1e300].
  double scale = d.norm() / std::sqrt(2.0);
  d.normalize();
  std::optional<double> before;
  for (int length = growth_continuation; length <= max_growth_continuation; length *= 2) {
    while (static_cast<int>(c.norms.size()) < length && scale < 1e300 && scale > 1e-300) {
      next.noalias() = map * d;
      const double norm = next.norm();
      if (!(norm > 0)) break;
      d = next / norm;
      scale *= norm;
      c.norms.push_back(scale);
    }
    const GrowthFit fit = fit_growth(c.norms);
    if (!fit.omitted.empty() || static_cast<int>(c.norms.size()) < length) break;
    if (before) {
      c.drift = std::abs(fit.growth - *before);
      if (c.drift <= fit.error_estimate) break;
    }
    before = fit.growth;
  }
  return c;
}

}  // namespace bladestab::detail
