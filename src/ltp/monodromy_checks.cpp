#include "ltp/monodromy_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/monodromy.hpp"

namespace bladestab {
namespace {

using cplx = std::complex<double>;

double reciprocal_error(const Eigen::VectorXcd& rho) {
  double worst = 0;
  for (Eigen::Index i = 0; i < rho.size() && std::abs(rho(i)) >= 1; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < rho.size(); ++j) nearest = std::min(nearest, std::abs(rho(i) * rho(j) - 1.0));
    worst = std::max(worst, nearest);
  }
  return worst;
}

// The dominant eigenpair (ρ, v) of Φ against x(T), v integrated over one period by RKF45.
struct DominantCheck {
  double residual = 0;          // ‖x(T) − ρ v‖ / |ρ|
  double multiplier_error = 0;  // |ρ' − ρ| / |ρ|, ρ' = wᴴx(T) / wᴴv with w the left eigenvector
};

// The residual carries every error of Φ in the direction of v, also those that move no multiplier
// (a Magnus Φ of a stable blade was 3.6e-5 off in v while its multipliers had settled to 2e-7);
// ρ' is first-order exact in x(T) and its error second order in v's: the check of the multiplier
// itself. Where ρ is ill-conditioned (a near-defective pair), the residual stands for it.
DominantCheck check_dominant(const Eigen::MatrixXd& phi, const LinearPeriodicSystem& sys, const CoefficientVariation& load,
                             double rtol) {
  // Φ/max|Φ_ij| has Φ's eigenvectors: past divergence Φ reaches 1e271, where the solver's norms of
  // Φ's own columns overflow and its eigenvectors come out non-finite.
  const double scale = phi.cwiseAbs().maxCoeff();
  Eigen::EigenSolver<Eigen::MatrixXd> eig(phi / scale, true);
  if (eig.info() != Eigen::Success || !eig.eigenvectors().allFinite()) {
    throw NumericalError("the eigenvectors of the monodromy matrix did not converge");
  }
  Eigen::Index k = 0;
  eig.eigenvalues().cwiseAbs().maxCoeff(&k);
  const cplx rho = scale * eig.eigenvalues()(k);
  Eigen::VectorXcd v = eig.eigenvectors().col(k).normalized();
  Eigen::VectorXcd start, end;  // v as integrated, and x(T)
  DominantCheck c;
  if (rho.imag() == 0) {
    // A real multiplier has a real eigenvector up to a phase: one column to integrate, not two.
    Eigen::Index largest = 0;
    v.cwiseAbs().maxCoeff(&largest);
    v *= std::conj(v(largest)) / std::abs(v(largest));
    const Eigen::VectorXd x = v.real();
    const Eigen::VectorXd xT = rkf45_propagate(sys, load, x, rtol, rtol * 1e-3);
    // stableNorm: x(T) grows like ρ, up to 1e271, whose squares overflow.
    c.residual = ((xT - rho.real() * x).stableNorm() + v.imag().norm() * (1 + std::abs(rho))) / std::abs(rho);
    start = x.cast<cplx>();
    end = xT.cast<cplx>();
  } else {
    Eigen::MatrixXd X(sys.state_size(), 2);
    X << v.real(), v.imag();
    const Eigen::MatrixXd XT = rkf45_propagate(sys, load, X, rtol, rtol * 1e-3);
    end = XT.col(0).cast<cplx>() + cplx(0, 1) * XT.col(1).cast<cplx>();
    start = v;
    c.residual = (end - rho * v).stableNorm() / std::abs(rho);
  }
  // wᴴ is row k of V⁻¹ (wᴴv = 1); ‖w‖‖v‖ is ρ's condition number κ: ~1 for the blade's separate
  // multipliers, 1e7 for the double one on a damped Mathieu boundary, where ρ' was 9e-4 off (its
  // error grows like κ) and the residual 6e-10.
  const Eigen::RowVectorXcd w = eig.eigenvectors().partialPivLu().inverse().row(k);
  const double condition = w.norm() * eig.eigenvectors().col(k).norm();
  c.multiplier_error = condition > 1e3 ? c.residual : std::abs((w * end)(0) / (w * start)(0) - rho) / std::abs(rho);
  return c;
}

}  // namespace

FloquetChecks check_monodromy(const Eigen::MatrixXd& phi, const Eigen::VectorXcd& rho, const LinearPeriodicSystem& sys,
                              double tol, bool integrate, const CoefficientVariation& load) {
  FloquetChecks c;
  // Φ carries relative errors of ~1e-13 (rounding over the steps), which its determinant magnifies by
  // Φ's condition (measured: 8e-7 at 1/rcond = 2.7e7); not informative beyond 1e10.
  const double rcond = Eigen::PartialPivLU<Eigen::MatrixXd>(phi).rcond();
  c.determinant_error = rcond < 1e-10 ? std::numeric_limits<double>::quiet_NaN() : liouville_error(phi, sys);
  // The partner 1/ρ of a large ρ is known only to the rounding of Φ, ~1e-13‖Φ‖ with ‖Φ‖ ~ max|ρ|;
  // ρ times it then carries 1e-13 max|ρ|² (measured 2e-13 at max|ρ| = 2.6e5): with a margin of 100,
  // the pairing tells nothing once that reaches 1 (max|ρ| ≳ 3e5; past 1e154 the product overflows).
  const double max_rho = rho.cwiseAbs().maxCoeff(), pair_rounding = 1e-11 * max_rho * max_rho;
  c.reciprocal_error = sys.hamiltonian && pair_rounding < 1 ? reciprocal_error(rho)
                                                            : std::numeric_limits<double>::quiet_NaN();
  const double rtol = std::clamp(tol * 1e-2, 1e-9, 1e-6);
  // An explicit integration of a stiff (unreduced) system would take far longer than the answer.
  const double integrated = load.rest ? load.varies_until / sys.period() : 1;
  const bool affordable = minimum_magnus_steps(sys) * integrated <= 8192;
  if (integrate && affordable) {
    const DominantCheck d = check_dominant(phi, sys, load, rtol);
    c.residual = d.residual;
    c.multiplier_error = d.multiplier_error;
  } else {
    c.residual = c.multiplier_error = std::numeric_limits<double>::quiet_NaN();
  }
  c.monodromy_max_abs_multiplier = rho.cwiseAbs().maxCoeff();
  const double allowed = std::max(10 * tol, 1e-8);
  if (c.determinant_error > allowed + 1e-13 / rcond) {
    throw NumericalError(fmt::format("monodromy check failed: det Φ(T) is off Liouville's exp(∫tr A) by {:.2g}; "
                                     "lower the tolerance", c.determinant_error));
  }
  if (c.reciprocal_error > allowed + pair_rounding) {
    throw NumericalError(fmt::format("monodromy check failed: the undamped multipliers are not reciprocal pairs "
                                     "(|ρ ρ' − 1| = {:.2g}); lower the tolerance", c.reciprocal_error));
  }
  // RKF45's global error over the many oscillations of a period reaches ~1e2–1e3 rtol.
  if (c.multiplier_error > allowed + 1e3 * rtol) {
    throw NumericalError(fmt::format("monodromy check failed: an independent RKF45 integration of the dominant "
                                     "Floquet vector gives a multiplier {:.2g} away; lower the tolerance",
                                     c.multiplier_error));
  }
  return c;
}

CoefficientVariation pulse_check_variation(const LinearPeriodicSystem& sys, const PeriodicPulse& pulse) {
  CoefficientVariation variation{pulse_variation(sys, pulse), {pulse.width}, 0, {}};
  if (pulse.impulse || !(pulse.width < sys.period())) return variation;
  Eigen::EigenSolver<Eigen::MatrixXd> eig(free_state_matrix(sys), true);
  if (eig.info() != Eigen::Success) return variation;
  const Eigen::MatrixXcd V = eig.eigenvectors();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(V);
  if (!(lu.rcond() > 1e-8)) return variation;
  const Eigen::VectorXcd growth = (eig.eigenvalues() * (sys.period() - pulse.width)).array().exp();
  variation.varies_until = pulse.width;
  variation.rest = [V, lu, growth](const Eigen::MatrixXd& X) -> Eigen::MatrixXd {
    return (V * (growth.asDiagonal() * lu.solve(X.cast<cplx>()))).real();
  };
  return variation;
}

}  // namespace bladestab
