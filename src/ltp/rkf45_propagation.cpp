#include "ltp/rkf45_propagation.hpp"

#include "bladestab/ltp/rkf45.hpp"

namespace bladestab {

CoefficientVariation series_variation(const LinearPeriodicSystem& sys) {
  return {[&sys](double t) { return sys.variation(t); }, {}, 0, {}};
}

namespace {

constexpr Eigen::Index few_columns = 4;

// Ẋ for X stored column after column in y. A system stated in modal form multiplies by the
// nonzero blocks of A₀ = [[0, D], [·, ·]] and B = [[0, 0], [·, 0]] only, a quarter of the full
// products' work; a few columns (an eigenvector) by Eigen's coefficient-wise product, as its
// blocked GEMM would spend more time packing the operand than multiplying.
OdeFunction propagation_rhs(const LinearPeriodicSystem& sys, const CoefficientVariation& variation, Eigen::Index n,
                            Eigen::Index columns, Eigen::MatrixXd& lower_left) {
  const Eigen::Index m = n / 2;
  const bool few = columns <= few_columns;
  if (sys.modal) lower_left.resize(m, m);
  return [&sys, &variation, n, m, columns, few, &lower_left](double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy) {
    dy.resize(y.size());
    const auto Y = Eigen::Map<const Eigen::MatrixXd>(y.data(), n, columns);
    auto D = Eigen::Map<Eigen::MatrixXd>(dy.data(), n, columns);
    const double f = variation.phi(t);
    if (sys.modal) {
      D.topRows(m).noalias() = sys.A0.topRightCorner(m, m).diagonal().asDiagonal() * Y.bottomRows(m);
      lower_left = sys.A0.bottomLeftCorner(m, m) + f * sys.B.bottomLeftCorner(m, m);
      if (few) {
        D.bottomRows(m).noalias() = lower_left.lazyProduct(Y.topRows(m));
        D.bottomRows(m).noalias() += sys.A0.bottomRightCorner(m, m).lazyProduct(Y.bottomRows(m));
      } else {
        D.bottomRows(m).noalias() = lower_left * Y.topRows(m);
        D.bottomRows(m).noalias() += sys.A0.bottomRightCorner(m, m) * Y.bottomRows(m);
      }
    } else if (few) {
      D.noalias() = sys.A0.lazyProduct(Y);
      D.noalias() += f * sys.B.lazyProduct(Y);
    } else {
      D.noalias() = sys.A0 * Y;
      D.noalias() += (f * sys.B) * Y;
    }
  };
}

}  // namespace

Eigen::MatrixXd rkf45_propagate(const LinearPeriodicSystem& sys, const CoefficientVariation& variation,
                                const Eigen::MatrixXd& X0, double rtol, double atol) {
  const Eigen::Index n = X0.rows(), columns = X0.cols();
  Eigen::MatrixXd lower_left;  // A₀'s lower-left block + φ(t) B's, reused by every evaluation
  const OdeFunction rhs = propagation_rhs(sys, variation, n, columns, lower_left);
  Eigen::VectorXd x = X0.reshaped();
  StepControl control;
  control.rtol = rtol;
  control.atol = atol;
  const double end = variation.rest ? variation.varies_until : sys.period();
  rkf45_integrate(rhs, x, 0, end, control, variation.breakpoints, {}, [](double, const Eigen::VectorXd&) {});
  return variation.rest ? variation.rest(x.reshaped(n, columns)) : Eigen::MatrixXd(x.reshaped(n, columns));
}

}  // namespace bladestab
