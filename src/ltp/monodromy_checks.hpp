#pragma once
// Checks of a monodromy matrix that do not share the Magnus propagator's failure modes
// (FloquetChecks, floquet.hpp): Liouville's determinant, the reciprocal pairs of a system stated
// Hamiltonian, and the dominant Floquet vector integrated by RKF45.
#include <Eigen/Dense>

#include "bladestab/ltp/floquet.hpp"
#include "ltp/rkf45_propagation.hpp"

namespace bladestab {

// The checks of Φ = monodromy with eigenvalues rho, at tolerance `tol`; the RKF45 one only when
// `integrate` and affordable. Throws NumericalError naming the check that failed.
FloquetChecks check_monodromy(const Eigen::MatrixXd& monodromy, const Eigen::VectorXcd& rho,
                              const LinearPeriodicSystem& system, double tol, bool integrate,
                              const CoefficientVariation& variation);

// The variation of a pulsed coefficient for the RKF45 check: RKF45 through the pulse, and the flight
// after it by the eigenvectors of A_free, e^{A τ} = V e^{Λτ} V⁻¹ (not the Padé exponential that
// the pulse monodromy takes). Where V is ill-conditioned, RKF45 integrates the whole period; an
// impulse is its rectangle, integrated by RKF45 too.
CoefficientVariation pulse_check_variation(const LinearPeriodicSystem& system, const PeriodicPulse& pulse);

}  // namespace bladestab
