#pragma once
// Free vibration at one speed: the gyroscopic (and possibly damped) quadratic eigenproblem
// (λ² M + λ C + K) q = 0, solved densely (LAPACK through Eigen) or, for large models, for the
// lowest modes only with ARPACK in shift-invert mode.
#include <complex>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/blade/second_order_system.hpp"

namespace bladestab {

const char* to_string(ModeFamily);  // ModeFamily: model.hpp

enum class EigenSolverKind { automatic, dense, arpack };
const char* to_string(EigenSolverKind);

// The work of one whole dense eigensolve of the first-order system of a model with `dofs` dofs
// (2·dofs states), in flops at cli::dense_flops_per_second (4e9/s); measured by
// bench/work_calibration.cpp (one core, 28 Nov 2026: undamped 2.0 ms at 48 dofs, 34 ms at 170,
// 0.20 s at 400; damped 8.3 ms, 0.12 s, 0.91 s).
//  - damped, the complex Schur form of dense_eigenpairs: 200 n³ + 10⁴ n², 1.4–4× its time;
//  - undamped within the static limits (`within_static_limits`), the Hermitian form of a
//    conservative gyroscopic system: 12 n³ + 4000 n², 1.4–1.7×;
//  - undamped where the limits are not known beforehand: 40 n³ + 8000 n², as a blade past its
//    static limit takes the complex form undamped too, whose time that count is about (0.9× at 170 dofs).
inline double whole_eigensolve_flops(double dofs, bool damped, bool within_static_limits = false) {
  if (damped) return (200 * dofs + 1e4) * dofs * dofs;
  return within_static_limits ? (12 * dofs + 4000) * dofs * dofs : (40 * dofs + 8000) * dofs * dofs;
}

// Eigenvalues λ (one per conjugate pair, Im λ ≥ 0) with their dof-space vectors q.
struct Eigenpairs {
  Eigen::VectorXcd values;
  Eigen::MatrixXcd vectors;
};

struct Mode {
  int index = 0;                   // 1-based, by frequency
  double frequency_hz = 0;         // Im λ / 2π
  double lambda = 0;               // Λ = ω L² sqrt(ρA/(EI)), ω = Im λ
  double damping_ratio = 0;        // −Re λ / |λ|
  ModeFamily family = ModeFamily::bending;
  std::vector<double> energy_share; // kinetic-energy share of each of the model's families
  std::complex<double> eigenvalue; // λ
  Eigen::VectorXcd shape;          // q, M-normalized: qᴴ M q = 1
};

struct ModalSolution {
  double speed_rad_s = 0;
  EigenSolverKind solver = EigenSolverKind::dense;  // the one actually used
  std::vector<Mode> modes;                          // sorted by |λ| (natural frequency)
};

// All eigenpairs, dense. Undamped gyroscopic systems with K > 0 go through a Hermitian form, so
// their eigenvalues come out exactly imaginary.
Eigenpairs dense_eigenpairs(const SecondOrderSystem& system);

// The `count` eigenpairs of smallest |λ| by ARPACK (dnaupd/dneupd), shift-invert about 0.
Eigenpairs arpack_eigenpairs(const SecondOrderSystem& system, int count);

// Models with at least this many dofs use ARPACK under EigenSolverKind::automatic.
constexpr int arpack_threshold_dofs = 120;

// The lowest `count` modes (all if count ≤ 0).
ModalSolution solve_modes(const BladeModel& model, const SecondOrderSystem& system, double speed_rad_s, int count,
                          EigenSolverKind solver = EigenSolverKind::automatic);

// The family holding most of q's kinetic energy (model.families), with every family's share
// qᴴ mass q into `shares` (in the order of model.families).
ModeFamily dominant_family(const BladeModel& model, const Eigen::VectorXcd& q, std::vector<double>& shares);

// Mass-weighted modal assurance criterion |aᴴ M b|² / ((aᴴ M a)(bᴴ M b)), in [0, 1].
double modal_assurance(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b, const Eigen::MatrixXd& M);

}  // namespace bladestab
