#include "bladestab/blade/undamped_modes.hpp"

#include <algorithm>
#include <vector>

#include <fmt/format.h>
#include <lapacke.h>

#include "bladestab/base/numerical_error.hpp"

namespace bladestab {

UndampedModes generalized_modes(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count, bool with_shapes) {
  Eigen::MatrixXd k = K, m = M;  // LAPACK overwrites both
  const lapack_int n = static_cast<lapack_int>(k.rows());
  const bool all = count <= 0 || count >= n;
  const char job = with_shapes ? 'V' : 'N';
  UndampedModes modes{Eigen::VectorXd(n), Eigen::MatrixXd()};
  lapack_int info = 0;
  if (all) {
    info = LAPACKE_dsygvd(LAPACK_COL_MAJOR, 1, job, 'L', n, k.data(), n, m.data(), n, modes.omega2.data());
    if (info == 0 && with_shapes) modes.shapes = std::move(k);
  } else {
    if (with_shapes) modes.shapes.resize(n, count);
    std::vector<lapack_int> failed(n);
    lapack_int found = 0;
    double unused = 0;
    info = LAPACKE_dsygvx(LAPACK_COL_MAJOR, 1, job, 'I', 'L', n, k.data(), n, m.data(), n, 0, 0, 1, count, 0.0, &found,
                          modes.omega2.data(), with_shapes ? modes.shapes.data() : &unused, with_shapes ? n : 1,
                          failed.data());
    if (found != count) info = info != 0 ? info : -1;
    modes.omega2.conservativeResize(count);
  }
  if (info != 0) {
    throw NumericalError(fmt::format("the undamped modes did not converge (LAPACK info {}): the stiffness or the "
                                     "mass matrix is not finite, not symmetric or the mass not positive definite",
                                     info));
  }
  return modes;
}

UndampedModes undamped_modes(const BladeModel& model, double speed, double tip_force_n, int count, bool with_shapes) {
  try {
    return generalized_modes(model.stiffness(speed, tip_force_n), model.M, count, with_shapes);
  } catch (const NumericalError&) {
    throw NumericalError(fmt::format("the modes of the blade did not converge at operation.speed_rad_s = {:g} with a "
                                     "tip load of {:.6g} N (load.fmax_over_fcr); the stiffness K(Ω) + F G is not "
                                     "finite or not symmetric there",
                                     speed, tip_force_n));
  }
}

}  // namespace bladestab
