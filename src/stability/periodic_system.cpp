#include "bladestab/stability/periodic_system.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/base/numerical_error.hpp"

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

double PeriodicSystem::period() const { return two_pi / angular_frequency; }

double PeriodicSystem::load_variation(double t) const {
  return fourier_sum(load, angular_frequency, t) - load.at(0).real();
}

Eigen::MatrixXcd PeriodicSystem::harmonic(int m) const {
  if (m == 0) return A0.cast<std::complex<double>>();
  const std::size_t a = static_cast<std::size_t>(std::abs(m));
  if (a >= load.size()) return Eigen::MatrixXcd::Zero(A0.rows(), A0.cols());
  const std::complex<double> F = m > 0 ? load[a] : std::conj(load[a]);
  return F * B.cast<std::complex<double>>();
}

PeriodicSystem periodic_system(const ReducedSystem& reduced, const LoadSeries& load) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> modes(reduced.K);  // M = I in the reduced coordinates
  if (modes.info() != Eigen::Success) {
    throw NumericalError("the modes of the reduced model did not converge: its stiffness is not finite (check "
                         "operation.speed_rad_s and load.fmax_over_fcr)");
  }
  const Eigen::VectorXd omega2 = modes.eigenvalues();
  const int n = reduced.size();
  Eigen::MatrixXd Phi = modes.eigenvectors();
  fix_mode_signs(Phi, reduced.basis);
  const Eigen::VectorXd w = omega2.cwiseSqrt();
  const Eigen::MatrixXd G = Phi.transpose() * reduced.G * Phi;
  const Eigen::MatrixXd C = Phi.transpose() * reduced.C * Phi;
  const double F0 = load.coefficients.at(0).real();

  PeriodicSystem sys;
  sys.A0 = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  sys.A0.topRightCorner(n, n) = w.asDiagonal();
  Eigen::MatrixXd stiffness = F0 * G;
  stiffness.diagonal() += omega2;
  sys.A0.bottomLeftCorner(n, n) = -stiffness * w.cwiseInverse().asDiagonal();
  sys.A0.bottomRightCorner(n, n) = -C;
  sys.B = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  sys.B.bottomLeftCorner(n, n) = -G * w.cwiseInverse().asDiagonal();
  sys.load = load.coefficients;
  sys.angular_frequency = load.angular_frequency;
  sys.modal_frequencies = w;
  sys.modal_G = G;
  sys.modal_C = C;
  sys.kept_modes = n;
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

int tongue_vectors(const BladeModel& model, const Scene& scene, double theta_max, int max_order) {
  Scene unloaded = scene;
  unloaded.load.fmax_over_fcr = 0;
  unloaded.load.pulse_frequency_hz = theta_max / two_pi;
  const Eigen::VectorXd omega =
      periodic_system(model, unloaded, load_series(unloaded), {ReductionKind::none, 0, 0}).modal_frequencies;
  return std::max(2, static_cast<int>((omega.array() < max_order * theta_max).count()));
}

}  // namespace bladestab
