#include "bladestab/blade/reduction.hpp"

#include <cmath>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/blade/static_limits.hpp"
#include "bladestab/blade/undamped_modes.hpp"

namespace bladestab {
namespace {

// An M-orthonormal basis of span(W): unit M-norm columns, then the eigenvectors of the Gram
// matrix WᵀMW; directions whose Gram eigenvalue is below 1e-10 are (nearly) dependent and dropped.
Eigen::MatrixXd m_orthonormal(Eigen::MatrixXd W, const Eigen::MatrixXd& M) {
  int kept = 0;
  for (Eigen::Index c = 0; c < W.cols(); ++c) {
    const double norm = std::sqrt(W.col(c).dot(M * W.col(c)));
    if (norm > 0 && std::isfinite(norm)) W.col(kept++) = W.col(c) / norm;
  }
  W.conservativeResize(Eigen::NoChange, kept);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(W.transpose() * M * W);
  const Eigen::VectorXd g = gram.eigenvalues();
  Eigen::Index first = 0;
  while (first < g.size() && g(first) < 1e-10) ++first;
  const Eigen::Index n = g.size() - first;
  return W * gram.eigenvectors().rightCols(n) * g.tail(n).cwiseSqrt().cwiseInverse().asDiagonal();
}

}  // namespace

ReducedSystem reduce(const BladeModel& model, double speed, const Eigen::MatrixXd& damping, double min_force_n,
                     const ReductionSpec& spec) {
  if (std::optional<InputError> past = static_limit_error(model, speed)) throw *past;
  const Eigen::MatrixXd C = damping + model.gyroscopic(speed);
  const int dofs = model.layout.size();
  Eigen::MatrixXd V;
  const int m = spec.vectors > 0 ? spec.vectors : default_reduction_vectors;
  // A model no larger than the reduced one would be is kept whole.
  if (spec.kind == ReductionKind::automatic && !reduction_keeps_whole(m, dofs)) {
    // A few modes of each load level (a subset solve: the whole decomposition at every map point
    // would take a tenth of a map's time).
    const UndampedModes unloaded = undamped_modes(model, speed, 0, m);
    const Eigen::MatrixXd corrections = model.stiffness(speed).ldlt().solve(C * unloaded.shapes);
    Eigen::MatrixXd W(dofs, 3 * m);
    W << unloaded.shapes, undamped_modes(model, speed, min_force_n, m).shapes, corrections;
    V = m_orthonormal(std::move(W), model.M);
  } else {
    const UndampedModes unloaded = undamped_modes(model, speed);
    int kept = dofs;
    if (spec.kind == ReductionKind::modal && spec.cutoff_hz > 0) {  // else every mode
      const Eigen::VectorXd f = unloaded.omega2.cwiseSqrt() / two_pi;
      kept = 1;
      while (kept < dofs && f(kept) < spec.cutoff_hz) ++kept;
    }
    V = unloaded.shapes.leftCols(kept);
  }
  ReducedSystem r;
  r.K = V.transpose() * model.stiffness(speed) * V;
  r.C = V.transpose() * C * V;
  r.G = V.transpose() * model.G * V;
  r.basis = std::move(V);
  r.full_size = dofs;
  r.undamped = damping.isZero(0);
  return r;
}

}  // namespace bladestab
