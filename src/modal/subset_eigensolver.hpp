#pragma once
// Dense eigensolvers for the per-speed solves of the reduced speed sweep (speed_sweep.cpp), on
// preallocated workspace: a subset of the eigenpairs of a symmetric matrix, and its inertia.
#include <vector>

#include <Eigen/Dense>
#include <lapacke.h>

namespace bladestab {

// Eigenpairs first .. first + count − 1 (0-based, ascending) of a symmetric matrix: Householder
// tridiagonalization; the wanted eigenvalues of the tridiagonal matrix by bisection on Sturm
// counts (all of them at once, each count narrowing every bracket); their eigenvectors by inverse
// iteration on it (O(n) each; reorthogonalized within clusters, as LAPACK's dstein does), carried
// back by the reflections. For these small matrices LAPACK's subset drivers (dsyevr, dstemr)
// spent three quarters of the whole Campbell run in their bisection, and Eigen's tridiagonal QR
// for all eigenvalues a third of it.
class SubsetEigensolver {
public:
  // Uses the lower triangle of `a`. Values in values().head(count), vectors in vectors();
  // `hints` (optional) are guesses of the values.
  void solve(const Eigen::MatrixXd& a, int first, int count, const Eigen::VectorXd* hints = nullptr);
  const Eigen::VectorXd& values() const { return values_; }
  const Eigen::MatrixXd& vectors() const { return vectors_; }

private:
  // Eigenvalues first .. first + count − 1 to a relative 1e-8: shifts for inverse iteration, whose
  // three steps need no more (the Ritz values are recomputed from the vectors). `hints`, if as
  // many, are guesses (the last speed's values): counts on either side of each narrow the
  // brackets at once; wrong guesses cost only those counts.
  void bisect(int first, int count, const Eigen::VectorXd* hints);

  // Sturm counts at points_ (the eigenvalues below each: signs of the LDLᵀ pivots of T − x I, the
  // points interleaved so that their divisions overlap); each count places every wanted
  // eigenvalue above or below its point.
  void narrow(int first, int count);

  // LU with partial pivoting of T − shift·I (tridiagonal; U gets a second superdiagonal).
  void factor(double eigenvalue);
  void solve_factored(Eigen::Ref<Eigen::VectorXd> z) const;

  Eigen::Tridiagonalization<Eigen::MatrixXd> tridiagonal_;
  Eigen::VectorXd diagonal_, sub_, squares_, values_, start_, u0_, u1_, u2_, l_;
  std::vector<double> lower_, upper_, points_, q_;
  std::vector<int> below_;
  double norm_ = 0, pivmin_ = 0;
  std::vector<bool> swapped_;
  Eigen::MatrixXd z_, vectors_;
  Eigen::VectorXd workspace_;
};

// Number of negative eigenvalues of a symmetric matrix (lower triangle) by Bunch–Kaufman LDLᵀ
// (dsytrf) and Sylvester's law of inertia; −1 if the matrix is singular.
class InertiaCounter {
public:
  void reserve(int n);
  int negatives(Eigen::MatrixXd& a);

private:
  int n_ = -1;
  std::vector<lapack_int> ipiv_;
  std::vector<double> work_;
};

}  // namespace bladestab
