#pragma once
// The undamped, non-gyroscopic modes of a Ritz model, (K(Ω) + F G) φ = ω² M φ (docs/theory.md §2, eq. (23)
// without C): the one eigenproblem of this kind, shared by the reduction's bases, modal damping,
// the transient's step cap and the crosscheck's seed.
#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"

namespace bladestab {

struct UndampedModes {
  Eigen::VectorXd omega2;  // ω², ascending
  Eigen::MatrixXd shapes;  // M-orthonormal columns (φᵀ M φ = I); empty when not asked for
};

// The `count` lowest modes of the symmetric pencil (K, M), M positive definite; all of them when
// `count` ≤ 0 or ≥ its size. A subset comes from LAPACK's dsygvx (tridiagonalization, bisection,
// inverse iteration), which for a few modes of a 48-dof model is several times cheaper than the
// whole decomposition (dsygvd). NumericalError when LAPACK does not converge.
UndampedModes generalized_modes(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count, bool with_shapes);

// The same for a model at speed Ω under a tip force F (tension positive): K(Ω) + F G. Its
// NumericalError names the speed and the load.
UndampedModes undamped_modes(const BladeModel& model, double speed_rad_s, double tip_force_n = 0, int count = 0,
                             bool with_shapes = true);

}  // namespace bladestab
