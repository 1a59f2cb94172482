#pragma once
// A linear time-periodic (LTP) system, the input of every kernel in ltp/ (docs/theory.md §4):
//
//   ẏ = A(t) y,   A(t) = A₀ + (f(t) − f₀) B,   f(t) = Σ_{|m| ≤ M} f_m e^{imθt},  f_{−m} = conj f_m,
//
// of period T = 2π/θ: a constant part and one scalar periodic coefficient times a constant matrix.
// A kernel takes the system as stated here and infers nothing from where it came from: the caller
// states its structure (Hamiltonian, second-order modal form), as a sparse solver is told that its
// matrix is symmetric.
//
// The second-order modal form η̈ + C η̇ + (Λ + f(t) G) η = 0, Λ = diag(ω_k²), is written in scaled
// first-order coordinates y = [D η; η̇], D = diag(ω_k) (modal_periodic_system):
//
//   A₀ = [[0, D], [−(Λ + f₀ G) D⁻¹, −C]],   B = [[0, 0], [−G D⁻¹, 0]],
//
// so that displacements and velocities carry the same units and Φ(T) is well conditioned.
#include <complex>
#include <optional>
#include <vector>

#include <Eigen/Dense>

namespace bladestab {

// η̈ + C η̇ + (Λ + f(t) G) η = 0 with Λ = diag(ω_k²): the second-order form behind a system.
struct ModalForm {
  Eigen::VectorXd stiffness;  // the diagonal of Λ, ω_k² > 0
  Eigen::MatrixXd G;          // stiffness per unit of the coefficient f
  Eigen::MatrixXd C;          // damping and gyroscopic coupling
  Eigen::VectorXd frequencies() const { return stiffness.cwiseSqrt(); }  // ω_k
};

struct LinearPeriodicSystem {
  Eigen::MatrixXd A0;                              // mean state matrix (with f₀ B)
  Eigen::MatrixXd B;                               // state matrix per unit of f
  std::vector<std::complex<double>> coefficients;  // f_m, m = 0..M
  double angular_frequency = 0;                    // θ
  // Stated by the caller: no damping (A(t) Hamiltonian, gyroscopic coupling at most), so the
  // multipliers come in pairs ρ, 1/ρ and the kernels check that they do.
  bool hamiltonian = false;
  // Stated by the caller: A₀ and B are the scaled first-order form of this modal form (the
  // boundary equations need it; the RKF45 check multiplies by its nonzero blocks only).
  std::optional<ModalForm> modal;

  double period() const;
  int state_size() const { return static_cast<int>(A0.rows()); }
  // f(t) − f₀ from the series.
  double variation(double t) const;
  // A_m of A(t) = Σ A_m e^{imθt}: A₀ for m = 0, f_m B otherwise.
  Eigen::MatrixXcd harmonic(int m) const;
  // The coefficient scaled by s (every f_m, so f₀ too; A₀ moves by (s − 1) f₀ B).
  LinearPeriodicSystem scaled(double s) const;
};

// The scaled first-order system of a modal form (the header's A₀ and B), with `modal` set.
LinearPeriodicSystem modal_periodic_system(ModalForm form, std::vector<std::complex<double>> coefficients,
                                           double angular_frequency, bool hamiltonian);

// Σ_{|m| ≤ M} f_m e^{imθt} for coefficients stored for m = 0..M (f_{−m} = conj f_m).
double fourier_sum(const std::vector<std::complex<double>>& coefficients, double angular_frequency, double t);

}  // namespace bladestab
