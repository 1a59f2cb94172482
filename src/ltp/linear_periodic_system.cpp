#include "bladestab/ltp/linear_periodic_system.hpp"

#include <cmath>

#include "bladestab/base/constants.hpp"

namespace bladestab {

double LinearPeriodicSystem::period() const { return two_pi / angular_frequency; }

double LinearPeriodicSystem::variation(double t) const {
  return fourier_sum(coefficients, angular_frequency, t) - coefficients.at(0).real();
}

Eigen::MatrixXcd LinearPeriodicSystem::harmonic(int m) const {
  if (m == 0) return A0.cast<std::complex<double>>();
  const std::size_t a = static_cast<std::size_t>(std::abs(m));
  if (a >= coefficients.size()) return Eigen::MatrixXcd::Zero(A0.rows(), A0.cols());
  const std::complex<double> f = m > 0 ? coefficients[a] : std::conj(coefficients[a]);
  return f * B.cast<std::complex<double>>();
}

LinearPeriodicSystem LinearPeriodicSystem::scaled(double s) const {
  LinearPeriodicSystem out = *this;
  const double f0 = coefficients.at(0).real();
  for (std::complex<double>& f : out.coefficients) f *= s;
  out.A0 += (out.coefficients[0].real() - f0) * B;
  return out;
}

LinearPeriodicSystem modal_periodic_system(ModalForm form, std::vector<std::complex<double>> coefficients,
                                           double angular_frequency, bool hamiltonian) {
  const Eigen::Index n = form.stiffness.size();
  const Eigen::VectorXd w = form.frequencies();
  const double f0 = coefficients.at(0).real();
  LinearPeriodicSystem sys;
  sys.A0 = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  sys.A0.topRightCorner(n, n) = w.asDiagonal();
  Eigen::MatrixXd stiffness = f0 * form.G;
  stiffness.diagonal() += form.stiffness;
  sys.A0.bottomLeftCorner(n, n) = -stiffness * w.cwiseInverse().asDiagonal();
  sys.A0.bottomRightCorner(n, n) = -form.C;
  sys.B = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  sys.B.bottomLeftCorner(n, n) = -form.G * w.cwiseInverse().asDiagonal();
  sys.coefficients = std::move(coefficients);
  sys.angular_frequency = angular_frequency;
  sys.hamiltonian = hamiltonian;
  sys.modal = std::move(form);
  return sys;
}

double fourier_sum(const std::vector<std::complex<double>>& coefficients, double angular_frequency, double t) {
  // Horner's rule in z = e^{iθt}: Σ_{m≥1} f_m z^m = z(f₁ + z(f₂ + …)), one exponential per call.
  const double f0 = coefficients.at(0).real();
  const std::complex<double> z = std::polar(1.0, angular_frequency * t);
  std::complex<double> sum = 0;
  for (std::size_t m = coefficients.size() - 1; m >= 1; --m) sum = z * (coefficients[m] + sum);
  return f0 + 2 * sum.real();
}

}  // namespace bladestab
