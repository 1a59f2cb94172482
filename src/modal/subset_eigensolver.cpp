#include "modal/subset_eigensolver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bladestab {

void SubsetEigensolver::solve(const Eigen::MatrixXd& a, int first, int count, const Eigen::VectorXd* hints) {
  const Eigen::Index n = a.rows();
  tridiagonal_.compute(a);
  diagonal_ = tridiagonal_.diagonal();
  sub_ = tridiagonal_.subDiagonal();
  bisect(first, count, hints);
  if (start_.size() != n) {
    start_.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) start_(i) = 1 + 0.5 * std::sin(1.7 * static_cast<double>(i));
  }
  z_.resize(n, count);
  const double cluster = 1e-3 * norm_;  // dstein's reorthogonalization threshold
  int cluster_start = 0;
  for (int j = 0; j < count; ++j) {
    if (j > 0 && values_(j) - values_(j - 1) > cluster) cluster_start = j;
    factor(values_(j));
    auto z = z_.col(j);
    z = start_;
    z(j % n) += 1;  // a different start for each member of a cluster
    for (int iteration = 0; iteration < 3; ++iteration) {
      z.normalize();
      solve_factored(z);
      for (int k = cluster_start; k < j; ++k) z -= z_.col(k).dot(z) * z_.col(k);
    }
    z.normalize();
  }
  // Back by the reflections one by one: Eigen's blocked product forms a triangular factor that
  // costs more than it saves at these sizes.
  vectors_ = z_;
  const Eigen::MatrixXd& packed = tridiagonal_.packedMatrix();
  const Eigen::VectorXd& tau = tridiagonal_.householderCoefficients();
  workspace_.resize(count);
  for (Eigen::Index k = n - 2; k >= 0; --k) {
    vectors_.bottomRows(n - k - 1).applyHouseholderOnTheLeft(packed.col(k).tail(n - k - 2), tau(k),
                                                               workspace_.data());
  }
}

void SubsetEigensolver::bisect(int first, int count, const Eigen::VectorXd* hints) {
  const Eigen::Index n = diagonal_.size();
  squares_ = sub_.cwiseAbs2();
  double lo = diagonal_(0), hi = diagonal_(0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double radius = (i > 0 ? std::abs(sub_(i - 1)) : 0.0) + (i + 1 < n ? std::abs(sub_(i)) : 0.0);
    lo = std::min(lo, diagonal_(i) - radius);
    hi = std::max(hi, diagonal_(i) + radius);
  }
  norm_ = std::max(std::abs(lo), std::abs(hi));
  pivmin_ = std::numeric_limits<double>::min() * std::max(1.0, squares_.size() ? squares_.maxCoeff() : 1.0);
  lower_.assign(count, lo);
  upper_.assign(count, hi);
  if (hints && hints->size() == count) {
    points_.resize(2 * static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
      points_[2 * k] = (*hints)(k) - 0.02 * std::abs((*hints)(k));
      points_[2 * k + 1] = (*hints)(k) + 0.02 * std::abs((*hints)(k));
    }
    narrow(first, count);
  }
  points_.resize(count);
  for (int iteration = 0; iteration < 200; ++iteration) {
    bool converged = true;
    for (int k = 0; k < count; ++k) {
      points_[k] = 0.5 * (lower_[k] + upper_[k]);
      converged = converged && upper_[k] - lower_[k] <= 1e-8 * std::abs(points_[k]) + 1e3 * pivmin_;
    }
    if (converged) break;
    narrow(first, count);
  }
  values_.resize(count);
  for (int k = 0; k < count; ++k) values_(k) = 0.5 * (lower_[k] + upper_[k]);
}

void SubsetEigensolver::narrow(int first, int count) {
  const Eigen::Index n = diagonal_.size();
  const std::size_t np = points_.size();
  q_.resize(np);
  below_.resize(np);
  const double* d = diagonal_.data();
  const double* e2 = squares_.data();
  for (std::size_t k = 0; k < np; ++k) {
    double q = d[0] - points_[k];
    if (std::abs(q) < pivmin_) q = -pivmin_;
    q_[k] = q;
    below_[k] = q < 0;
  }
  for (Eigen::Index i = 1; i < n; ++i) {
    const double di = d[i], ei = e2[i - 1];
    for (std::size_t k = 0; k < np; ++k) {
      double q = (di - points_[k]) - ei / q_[k];
      if (std::abs(q) < pivmin_) q = -pivmin_;
      q_[k] = q;
      below_[k] += q < 0;
    }
  }
  for (std::size_t k = 0; k < np; ++k) {
    for (int j = 0; j < count; ++j) {
      if (below_[k] > first + j) {
        upper_[j] = std::min(upper_[j], points_[k]);
      } else {
        lower_[j] = std::max(lower_[j], points_[k]);
      }
    }
  }
}

void SubsetEigensolver::factor(double eigenvalue) {
  const double norm = norm_;
  // A shift a hair off the eigenvalue keeps the factorization regular.
  const double shift = eigenvalue + 4 * std::numeric_limits<double>::epsilon() * norm;
  const Eigen::Index n = diagonal_.size();
  u0_.resize(n), u1_.resize(n), u2_.resize(n), l_.resize(n), swapped_.resize(n);
  const double tiny = std::numeric_limits<double>::epsilon() * std::max(norm, std::numeric_limits<double>::min());
  double d = diagonal_(0) - shift, up = n > 1 ? sub_(0) : 0.0;
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    const double below = sub_(i), next_diag = diagonal_(i + 1) - shift, next_up = i + 2 < n ? sub_(i + 1) : 0.0;
    if (std::abs(d) >= std::abs(below)) {  // no swap
      if (d == 0) d = tiny;
      const double m = below / d;
      u0_(i) = d, u1_(i) = up, u2_(i) = 0, l_(i) = m, swapped_[i] = false;
      d = next_diag - m * up;
      up = next_up;
    } else {  // swap rows i and i + 1
      const double m = d / below;
      u0_(i) = below, u1_(i) = next_diag, u2_(i) = next_up, l_(i) = m, swapped_[i] = true;
      d = up - m * next_diag;
      up = -m * next_up;
    }
  }
  u0_(n - 1) = d == 0 ? tiny : d;
}

void SubsetEigensolver::solve_factored(Eigen::Ref<Eigen::VectorXd> z) const {
  const Eigen::Index n = z.size();
  for (Eigen::Index i = 0; i + 1 < n; ++i) {  // L⁻¹ with the row swaps
    if (swapped_[i]) std::swap(z(i), z(i + 1));
    z(i + 1) -= l_(i) * z(i);
  }
  for (Eigen::Index i = n - 1; i >= 0; --i) {  // U⁻¹
    double v = z(i);
    if (i + 1 < n) v -= u1_(i) * z(i + 1);
    if (i + 2 < n) v -= u2_(i) * z(i + 2);
    z(i) = v / u0_(i);
  }
}

void InertiaCounter::reserve(int n) {
  if (n == n_) return;
  n_ = n;
  ipiv_.resize(n);
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
  double work_size = 0;
  LAPACKE_dsytrf_work(LAPACK_COL_MAJOR, 'L', n, a.data(), n, ipiv_.data(), &work_size, -1);
  work_.resize(std::max<std::size_t>(1, static_cast<std::size_t>(work_size)));
}

int InertiaCounter::negatives(Eigen::MatrixXd& a) {
  const lapack_int n = static_cast<lapack_int>(a.rows());
  reserve(static_cast<int>(n));
  const lapack_int info = LAPACKE_dsytrf_work(LAPACK_COL_MAJOR, 'L', n, a.data(), n, ipiv_.data(), work_.data(),
                                              static_cast<lapack_int>(work_.size()));
  if (info != 0) return -1;  // info > 0: an exactly singular D
  int negative = 0;
  for (lapack_int k = 0; k < n; ++k) {
    if (ipiv_[k] > 0) {
      if (a(k, k) < 0) ++negative;
    } else {  // 2×2 block in rows k, k+1
      const double d11 = a(k, k), d21 = a(k + 1, k), d22 = a(k + 1, k + 1);
      const double det = d11 * d22 - d21 * d21;
      if (det < 0) {
        negative += 1;
      } else if (det > 0) {
        negative += d11 + d22 < 0 ? 2 : 0;
      } else {
        return -1;
      }
      ++k;
    }
  }
  return negative;
}

}  // namespace bladestab
