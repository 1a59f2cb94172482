#include "bladestab/periodic_system.hpp"

#include <cmath>

#include <fmt/format.h>

#include "bladestab/damping.hpp"
#include "bladestab/input_error.hpp"

namespace bladestab {

namespace {
constexpr double two_pi = 6.28318530717958647692;
}

double PeriodicSystem::period() const { return two_pi / angular_frequency; }

double PeriodicSystem::load_variation(double t) const {
  double f = 0;
  for (std::size_t m = 1; m < load.size(); ++m) {
    f += 2 * std::real(load[m] * std::exp(std::complex<double>(0, m * angular_frequency * t)));
  }
  return f;
}

Eigen::MatrixXcd PeriodicSystem::harmonic(int m) const {
  if (m == 0) return A0.cast<std::complex<double>>();
  const std::size_t a = static_cast<std::size_t>(std::abs(m));
  if (a >= load.size()) return Eigen::MatrixXcd::Zero(A0.rows(), A0.cols());
  const std::complex<double> F = m > 0 ? load[a] : std::conj(load[a]);
  return F * B.cast<std::complex<double>>();
}

PeriodicSystem periodic_system(const BladeModel& model, double speed, const Eigen::MatrixXd& damping,
                               const LoadSeries& load, double cutoff_hz) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(model.stiffness(speed), model.M);
  if (modes.info() != Eigen::Success) throw std::runtime_error("modal decomposition failed");
  const Eigen::VectorXd omega2 = modes.eigenvalues();
  if (omega2.minCoeff() <= 0) {
    throw InputError(fmt::format("operation.speed_rad_s = {}: the unloaded blade is statically unstable at this speed",
                                 speed));
  }
  int kept = static_cast<int>(omega2.size());
  if (cutoff_hz > 0) {
    kept = 0;
    while (kept < omega2.size() && std::sqrt(omega2(kept)) / two_pi < cutoff_hz) ++kept;
    kept = std::max(kept, 1);
  }
  const Eigen::MatrixXd Phi = modes.eigenvectors().leftCols(kept);
  const Eigen::VectorXd w = omega2.head(kept).cwiseSqrt();
  const Eigen::MatrixXd G = Phi.transpose() * model.G * Phi;
  const Eigen::MatrixXd C = Phi.transpose() * (damping + model.gyroscopic(speed)) * Phi;
  const double F0 = load.coefficients.at(0).real();

  PeriodicSystem sys;
  const int n = kept;
  sys.A0 = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  sys.A0.topRightCorner(n, n) = w.asDiagonal();
  Eigen::MatrixXd stiffness = F0 * G;
  stiffness.diagonal() += omega2.head(kept);
  sys.A0.bottomLeftCorner(n, n) = -stiffness * w.cwiseInverse().asDiagonal();
  sys.A0.bottomRightCorner(n, n) = -C;
  sys.B = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  sys.B.bottomLeftCorner(n, n) = -G * w.cwiseInverse().asDiagonal();
  sys.load = load.coefficients;
  sys.angular_frequency = load.angular_frequency;
  sys.modal_frequencies = w;
  sys.modal_G = G;
  sys.modal_C = C;
  sys.kept_modes = kept;
  sys.all_modes = static_cast<int>(omega2.size());
  return sys;
}

PeriodicSystem periodic_system(const BladeModel& model, const Scene& scene, const LoadSeries& load,
                               double cutoff_hz) {
  const double speed = scene.operation.speed_rad_s;
  return periodic_system(model, speed, damping_matrix(model, scene.damping, speed), load, cutoff_hz);
}

}  // namespace bladestab
