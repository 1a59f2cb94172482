#include "bladestab/blade/damping.hpp"

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/blade/static_limits.hpp"
#include "bladestab/blade/undamped_modes.hpp"

namespace bladestab {

Eigen::MatrixXd damping_matrix(const BladeModel& model, const DampingSpec& spec, double speed) {
  const int n = model.layout.size();
  switch (spec.model) {
    case DampingModel::none:
      return Eigen::MatrixXd::Zero(n, n);
    case DampingModel::paper:
      check_damping_speed(spec, speed, "the speed Ω");
      return (2 * spec.ratio / speed) * model.elastic_stiffness();  // (37)
    case DampingModel::rayleigh: {
      // ζ(ω) = α/(2ω) + βω/2 equal to ζ at ω1 and ω2.
      const double w1 = two_pi * spec.frequencies_hz[0], w2 = two_pi * spec.frequencies_hz[1];
      const double alpha = 2 * spec.ratio * w1 * w2 / (w1 + w2);
      const double beta = 2 * spec.ratio / (w1 + w2);
      return alpha * model.M + beta * model.elastic_stiffness();
    }
    case DampingModel::modal: {
      // Modal damping needs the modes of a blade within its static limits (all ω² > 0).
      if (std::optional<InputError> past = static_limit_error(model, speed)) throw *past;
      const UndampedModes modes = undamped_modes(model, speed);
      const Eigen::MatrixXd MPhi = model.M * modes.shapes;  // Φ is M-orthonormal
      const Eigen::VectorXd two_zeta_omega = 2 * spec.ratio * modes.omega2.cwiseSqrt();
      Eigen::MatrixXd C = MPhi * two_zeta_omega.asDiagonal() * MPhi.transpose();
      return 0.5 * (C + C.transpose());
    }
  }
  return Eigen::MatrixXd::Zero(n, n);
}

}  // namespace bladestab
