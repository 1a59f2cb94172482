#pragma once
// A linear second-order system M q̈ + C q̇ + K q = 0 at one operating point: what the eigen- and
// stability solvers consume.
#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"

namespace bladestab {

struct SecondOrderSystem {
  Eigen::MatrixXd M, C, K;
};

// M, C_D + Ω C_G1, K_S + Ω² K_C1 + F G at speed Ω and a constant tip force F (tension > 0).
inline SecondOrderSystem system_at(const BladeModel& model, double speed_rad_s, const Eigen::MatrixXd& damping,
                                   double tip_force_n = 0) {
  return {model.M, damping + model.gyroscopic(speed_rad_s), model.stiffness(speed_rad_s, tip_force_n)};
}

}  // namespace bladestab
