#include "bladestab/blade/reduction.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

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

// A basis V and the sizes of its column blocks (ReducedSystem::blocks).
struct ReducedBasis {
  Eigen::MatrixXd V;
  std::vector<int> blocks;
};

// The coordinates of the axial field against the others (rotation and bending) of an undamped
// blade: the two are coupled by the gyroscopic matrix alone, M, K_S, K_C1 and G having no entry
// between them (docs/theory.md §2.4). Empty where the model has no axial field or couples it
// otherwise, and with damping, which breaks the symmetry the split serves (its tiny share in a
// gyroscopic correction would come out as a basis vector of its own and move which nearly
// dependent directions the Gram step keeps).
std::vector<std::pair<int, int>> decoupled_fields(const BladeModel& model, const Eigen::MatrixXd& damping) {
  const int a = model.layout.axial_offset(), na = model.layout.axial_count;
  const auto uncoupled = [&](const Eigen::MatrixXd& X) {
    return X.block(0, a, a, na).isZero(0) && X.block(a, 0, na, a).isZero(0);
  };
  if (a == 0 || na == 0 || !damping.isZero(0)) return {};
  if (!(uncoupled(model.M) && uncoupled(model.K_S) && uncoupled(model.K_C1) && uncoupled(model.G))) return {};
  return {{0, a}, {a, na}};
}

// An M-orthonormal basis of span(W) whose vectors each lie in one group of decoupled fields: every
// column of W is cut into its parts in the groups, a part kept where its M-norm is above 1e-8 of
// the column's (below, it is the rounding of the eigensolver that made the column), and each
// group's parts made M-orthonormal apart. The reduced M, K(Ω) and G are then block diagonal to the
// last bit, and so are the modes (reduced_modes): an axial mode stays axial, as in the continuum.
ReducedBasis field_pure_basis(const Eigen::MatrixXd& W, const BladeModel& model, const Eigen::MatrixXd& damping) {
  const std::vector<std::pair<int, int>> groups = decoupled_fields(model, damping);
  if (groups.empty()) return {m_orthonormal(W, model.M), {}};
  std::vector<Eigen::MatrixXd> parts;
  Eigen::Index columns = 0;
  for (const auto& [offset, count] : groups) {
    Eigen::MatrixXd part = Eigen::MatrixXd::Zero(W.rows(), W.cols());
    int kept = 0;
    for (Eigen::Index c = 0; c < W.cols(); ++c) {
      const auto piece = W.col(c).segment(offset, count);
      const double whole = W.col(c).dot(model.M * W.col(c));
      const double own = piece.dot(model.M.block(offset, offset, count, count) * piece);
      if (own > 1e-16 * whole) part.col(kept++).segment(offset, count) = piece;
    }
    if (kept == 0) continue;  // no column reaches this group (the automatic reduction without Coriolis: no axial part)
    part.conservativeResize(Eigen::NoChange, kept);
    parts.push_back(m_orthonormal(std::move(part), model.M));
    columns += parts.back().cols();
  }
  ReducedBasis basis{Eigen::MatrixXd(W.rows(), columns), {}};
  Eigen::Index at = 0;
  for (const Eigen::MatrixXd& part : parts) {
    basis.V.middleCols(at, part.cols()) = part;
    at += part.cols();
    basis.blocks.push_back(static_cast<int>(part.cols()));
  }
  return basis;
}

}  // namespace

ReducedModes reduced_modes(const ReducedSystem& reduced) {
  const Eigen::Index n = reduced.size();
  Eigen::VectorXd omega2(n);
  Eigen::MatrixXd shapes = Eigen::MatrixXd::Zero(n, n);
  Eigen::Index at = 0;
  // A system stated without blocks is one block.
  const std::vector<int> blocks = reduced.blocks.empty() ? std::vector<int>{static_cast<int>(n)} : reduced.blocks;
  for (const int size : blocks) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> block(reduced.K.block(at, at, size, size));
    if (block.info() != Eigen::Success) return {{}, {}, false};
    omega2.segment(at, size) = block.eigenvalues();
    shapes.block(at, at, size, size) = block.eigenvectors();
    at += size;
  }
  // Ascending over the blocks, as one eigensolver would give them.
  std::vector<Eigen::Index> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index i, Eigen::Index j) { return omega2(i) < omega2(j); });
  ReducedModes modes{Eigen::VectorXd(n), Eigen::MatrixXd(n, n), true};
  for (Eigen::Index k = 0; k < n; ++k) {
    modes.omega2(k) = omega2(order[k]);
    modes.shapes.col(k) = shapes.col(order[k]);
  }
  return modes;
}

ReducedSystem reduce(const BladeModel& model, double speed, const Eigen::MatrixXd& damping, double min_force_n,
                     const ReductionSpec& spec) {
  if (std::optional<InputError> past = static_limit_error(model, speed)) throw *past;
  const Eigen::MatrixXd C = damping + model.gyroscopic(speed);
  const int dofs = model.layout.size();
  ReducedBasis basis;
  const int m = spec.vectors > 0 ? spec.vectors : default_reduction_vectors;
  // A model no larger than the reduced one would be is kept whole.
  if (spec.kind == ReductionKind::automatic && !reduction_keeps_whole(m, dofs)) {
    // A few modes of each load level (a subset solve: the whole decomposition at every map point
    // would take a tenth of a map's time).
    const UndampedModes unloaded = undamped_modes(model, speed, 0, m);
    const Eigen::MatrixXd corrections = model.stiffness(speed).ldlt().solve(C * unloaded.shapes);
    Eigen::MatrixXd W(dofs, 3 * m);
    W << unloaded.shapes, undamped_modes(model, speed, min_force_n, m).shapes, corrections;
    basis = field_pure_basis(W, model, damping);
  } else {
    const UndampedModes unloaded = undamped_modes(model, speed);
    int kept = dofs;
    if (spec.kind == ReductionKind::modal && spec.cutoff_hz > 0) {  // else every mode
      const Eigen::VectorXd f = unloaded.omega2.cwiseSqrt() / two_pi;
      kept = 1;
      while (kept < dofs && f(kept) < spec.cutoff_hz) ++kept;
    }
    basis = field_pure_basis(unloaded.shapes.leftCols(kept), model, damping);
  }
  const Eigen::MatrixXd& V = basis.V;
  ReducedSystem r;
  r.K = V.transpose() * model.stiffness(speed) * V;
  r.C = V.transpose() * C * V;
  r.G = V.transpose() * model.G * V;
  r.basis = std::move(basis.V);
  r.blocks = std::move(basis.blocks);
  r.full_size = dofs;
  r.undamped = damping.isZero(0);
  return r;
}

}  // namespace bladestab
