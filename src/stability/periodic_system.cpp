#include "bladestab/stability/periodic_system.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/monodromy.hpp"

namespace bladestab {

namespace {

// Eigenvectors are defined up to sign, and which sign LAPACK returns depends on rounding (the
// build's vectorization, BLAS threads). The state coordinates are fixed here: each mode's shape in
// the Ritz coordinates has its largest entry positive, so the periodic system (and what
// --export-matrices writes) is the same on every build.
void fix_mode_signs(Eigen::MatrixXd& Phi, const Eigen::MatrixXd& basis) {
  const Eigen::MatrixXd shapes = basis * Phi;
  for (Eigen::Index j = 0; j < Phi.cols(); ++j) {
    Eigen::Index largest = 0;
    shapes.col(j).cwiseAbs().maxCoeff(&largest);
    if (shapes(largest, j) < 0) Phi.col(j) = -Phi.col(j);
  }
}

}  // namespace

PeriodicSystem periodic_system(const ReducedSystem& reduced, const LoadSeries& load) {
  ReducedModes modes = reduced_modes(reduced);
  if (!modes.converged) {
    throw NumericalError("the modes of the reduced model did not converge: its stiffness is not finite (check "
                         "operation.speed_rad_s and load.fmax_over_fcr)");
  }
  Eigen::MatrixXd& Phi = modes.shapes;
  fix_mode_signs(Phi, reduced.basis);
  ModalForm form{modes.omega2, Phi.transpose() * reduced.G * Phi, Phi.transpose() * reduced.C * Phi};
  PeriodicSystem sys;
  static_cast<LinearPeriodicSystem&>(sys) =
      modal_periodic_system(std::move(form), load.coefficients, load.angular_frequency, reduced.undamped);
  sys.kept_modes = reduced.size();
  sys.all_modes = reduced.full_size;
  return sys;
}

PeriodicSystem periodic_system(const BladeModel& model, double speed, const Eigen::MatrixXd& damping,
                               const LoadSeries& load, const ReductionSpec& reduction) {
  return periodic_system(reduce(model, speed, damping, load.minimum(), reduction), load);
}

PeriodicSystem periodic_system(const BladeModel& model, const Scene& scene, const LoadSeries& load,
                               const ReductionSpec& reduction) {
  const double speed = scene.operation.speed_rad_s;
  return periodic_system(model, speed, damping_matrix(model, scene.damping, speed), load, reduction);
}

bool true_train_on_whole_model(const PeriodicSystem& whole, const PulseTrain& train) {
  return minimum_magnus_steps(whole) * train.contact_time_s / train.period_s <= 4096;
}

int tongue_vectors(const BladeModel& model, const Scene& scene, double theta_max, int max_order) {
  Scene unloaded = scene;
  unloaded.load.fmax_over_fcr = 0;
  unloaded.load.pulse_frequency_hz = theta_max / two_pi;
  // The frequencies need no load, only a contact within the period at θ_max (a speed-plane map
  // asks at its lowest speed for its highest θ, where 0.3 of a revolution at 150 rad/s outlasts it).
  const double speed = scene.operation.speed_rad_s;
  if (speed > 0) unloaded.load.contact_time_rev = std::min(scene.load.contact_time_rev, speed / theta_max);
  const Eigen::VectorXd omega =
      periodic_system(model, unloaded, load_series(unloaded), {ReductionKind::none, 0, 0}).modal->frequencies();
  return std::max(2, static_cast<int>((omega.array() < max_order * theta_max).count()));
}

}  // namespace bladestab
