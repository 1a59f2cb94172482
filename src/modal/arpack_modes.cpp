// Lowest modes of a large model with ARPACK's implicitly restarted Arnoldi method in
// shift-invert mode about σ = 0. With z = [q; q̇/s] the first-order form is B ż = A z,
// B = diag(I, M), A = [[0, s I], [−K/s, −C]]; ARPACK iterates OP = A⁻¹B, whose eigenvalues 1/λ are
// largest in magnitude for the smallest |λ|. Applying A⁻¹ costs one solve with K:
//   A [a; b] = [c; d]  ⇔  b = c/s,  a = −s K⁻¹ (d + C b).
// The scale s, about the lowest |λ| (balanced_scale), makes both blocks of OP = [[−K⁻¹C, −s K⁻¹M],
// [I/s, 0]] about 1/|λ₁|: with s = 1 the identity block dwarfs them (‖OP‖ ≈ 1 for eigenvalues of
// 1e-4), and Ritz values converged to ε‖OP‖ were 1e-8 off (the axial mode at 64 terms).
//
// ARPACK is not reentrant: between its reverse-communication calls dnaupd, dnaup2, dnaitr and
// dnapps keep the run's state (pointers into workl, iteration counts, norms) in Fortran SAVE
// variables, and every routine writes the COMMON blocks debug_ and timing_. Two threads inside it
// at once take each other's offsets, write past their own arrays and corrupt the heap. So one run
// at a time per process: a lock held from the first dnaupd call to the end of dneupd. The rest of
// the solve (the factorization, the Ritz vectors' lifting) runs unlocked.
#include <arpack/arpack.hpp>
#undef I  // <complex.h>, pulled in by arpack.hpp, defines I as a macro

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <lapacke.h>

#include "bladestab/modal/modes.hpp"

namespace bladestab {
namespace {

std::mutex& arpack_lock() {
  static std::mutex lock;
  return lock;
}

// The `count` eigenpairs of least |λ| (Im λ ≥ 0) from ARPACK's `converged` Ritz pairs of OP, whose
// values are ν = 1/λ; a complex pair occupies columns j, j+1 of Z as real and imaginary parts.
Eigenpairs lowest_eigenpairs(const std::vector<double>& dr, const std::vector<double>& di, const std::vector<double>& Z,
                             int converged, int n, int count) {
  const int dim = 2 * n;
  std::vector<std::pair<std::complex<double>, Eigen::VectorXcd>> found;
  for (int j = 0; j < converged; ++j) {
    const Eigen::Map<const Eigen::VectorXd> re(&Z[static_cast<std::size_t>(j) * dim], dim);
    Eigen::VectorXcd z = re.cast<std::complex<double>>();
    const std::complex<double> nu(dr[j], di[j]);
    if (di[j] != 0) {
      if (j + 1 >= converged) break;  // half a pair at the end
      const Eigen::Map<const Eigen::VectorXd> im(&Z[static_cast<std::size_t>(j + 1) * dim], dim);
      z.imag() = im;
      ++j;
    }
    // λ = 1/ν; keep the member with Im λ ≥ 0, i.e. Im ν ≤ 0 (the conjugate has the conjugate vector).
    const std::complex<double> lambda = 1.0 / nu;
    if (lambda.imag() >= 0) {
      found.emplace_back(lambda, z.head(n));
    } else {
      found.emplace_back(std::conj(lambda), z.head(n).conjugate());
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return std::abs(a.first) < std::abs(b.first); });
  if (static_cast<int>(found.size()) > count) found.resize(count);
  Eigenpairs out{Eigen::VectorXcd(found.size()), Eigen::MatrixXcd(n, found.size())};
  for (std::size_t k = 0; k < found.size(); ++k) {
    out.values(k) = found[k].first;
    out.vectors.col(k) = found[k].second;
  }
  return out;
}

// About the least |λ| of K q = −λ² M q: the Rayleigh quotient's root after three inverse iterations
// from a vector of ones; 1 where that fails (the scale only balances OP, any order of magnitude near
// it serves).
double balanced_scale(const Eigen::PartialPivLU<Eigen::MatrixXd>& K, const SecondOrderSystem& sys) {
  Eigen::VectorXd x = Eigen::VectorXd::Ones(sys.M.rows());
  for (int k = 0; k < 3; ++k) {
    x = K.solve(sys.M * x);
    x /= x.norm();
  }
  const double s = std::sqrt(std::abs(x.dot(sys.K * x)) / x.dot(sys.M * x));
  return std::isfinite(s) && s > 0 ? s : 1.0;
}

}  // namespace

Eigenpairs arpack_eigenpairs(const SecondOrderSystem& sys, int count) {
  const int n = static_cast<int>(sys.M.rows());
  const int dim = 2 * n;
  const int nev = std::min(2 * count + 1, dim - 2);  // both members of each conjugate pair, plus one spare
  const int ncv = std::min(dim, std::max(2 * nev + 1, 30));
  if (count < 1 || nev < 2 * count) {
    throw std::invalid_argument(fmt::format("ARPACK needs fewer modes than the model has ({} of {})", count, n));
  }
  const Eigen::PartialPivLU<Eigen::MatrixXd> K(sys.K);
  const double scale = balanced_scale(K, sys);

  std::vector<double> resid(dim), V(static_cast<std::size_t>(dim) * ncv), workd(3 * dim);
  const int lworkl = 3 * ncv * ncv + 6 * ncv;
  std::vector<double> workl(lworkl);
  a_int iparam[11] = {1, 0, 10 * dim + 1000, 1, 0, 0, 1, 0, 0, 0, 0};  // exact shifts, mode 1 (OP given)
  a_int ipntr[14] = {0};
  a_int ido = 0;
  const double tol = 0;  // machine precision
  // The starting vector is the solve's own (info = 1): ARPACK draws it with dlarnv from a seed it
  // keeps between runs, so an answer would depend on the solves before it, and on threads. Here
  // it is the vector ARPACK draws in its first run: uniform in (−1, 1) from the seed (1, 3, 5, 7).
  lapack_int seed[4] = {1, 3, 5, 7};
  LAPACKE_dlarnv(2, seed, dim, resid.data());
  a_int info = 1;

  auto apply_op = [&](const double* x, double* y) {
    const Eigen::Map<const Eigen::VectorXd> c(x, n), x2(x + n, n);
    const Eigen::VectorXd d = sys.M * x2;
    Eigen::Map<Eigen::VectorXd> a(y, n), b(y + n, n);
    b = c / scale;
    a = -scale * K.solve(d + sys.C * b);
  };

  std::unique_lock<std::mutex> one_run_at_a_time(arpack_lock());
  while (true) {
    arpack::naupd(ido, arpack::bmat::identity, dim, arpack::which::largest_magnitude, nev, tol, resid.data(), ncv,
                  V.data(), dim, iparam, ipntr, workd.data(), workl.data(), lworkl, info);
    if (ido != -1 && ido != 1) break;
    apply_op(&workd[ipntr[0] - 1], &workd[ipntr[1] - 1]);
  }
  // info = 1 (iteration limit) still leaves the converged pairs usable; need both members of `count` pairs.
  if (info < 0 || iparam[4] < 2 * count) {
    throw std::runtime_error(fmt::format("ARPACK dnaupd failed (info {}, {} of {} converged)", info, iparam[4], nev));
  }

  std::vector<a_int> select(ncv, 1);
  std::vector<double> dr(nev + 1), di(nev + 1), Z(static_cast<std::size_t>(dim) * (nev + 1)), workev(3 * ncv);
  arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), dr.data(), di.data(), Z.data(), dim, 0.0, 0.0,
                workev.data(), arpack::bmat::identity, dim, arpack::which::largest_magnitude, nev, tol,
                resid.data(), ncv, V.data(), dim, iparam, ipntr, workd.data(), workl.data(), lworkl, info);
  one_run_at_a_time.unlock();
  if (info != 0) throw std::runtime_error(fmt::format("ARPACK dneupd failed (info {})", info));

  return lowest_eigenpairs(dr, di, Z, static_cast<int>(iparam[4]), n, count);
}

}  // namespace bladestab
