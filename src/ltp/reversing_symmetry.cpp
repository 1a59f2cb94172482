#include "bladestab/ltp/reversing_symmetry.hpp"

#include <cmath>
#include <vector>

namespace bladestab {
namespace {

// Whether the entry (i, j) of A₀ or B couples its two coordinates beyond their rounding.
struct CouplingPattern {
  const Eigen::MatrixXd& A0;
  const Eigen::MatrixXd& B;
  double a_floor, b_floor;
  bool couples(Eigen::Index i, Eigen::Index j) const {
    return std::abs(A0(i, j)) > a_floor || std::abs(B(i, j)) > b_floor;
  }
};

}  // namespace

std::optional<Eigen::VectorXd> reversing_signature(const LinearPeriodicSystem& sys) {
  for (const std::complex<double>& f : sys.coefficients) {
    if (std::abs(f.imag()) > 1e-14 * std::abs(f)) return std::nullopt;  // f is not even
  }
  return reversing_signature(sys.A0, sys.B);
}

std::optional<Eigen::VectorXd> reversing_signature(const Eigen::MatrixXd& A0, const Eigen::MatrixXd& B) {
  const CouplingPattern pattern{A0, B, 1e-13 * A0.cwiseAbs().maxCoeff(), 1e-13 * B.cwiseAbs().maxCoeff()};
  const Eigen::Index n = A0.rows();
  // r_i a_ij r_j = −a_ij: every coupling joins coordinates of opposite sign. Two-colour the
  // coupling graph from each uncoloured coordinate; a coupling within one colour (a diagonal entry
  // among them) leaves no signature.
  Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Index> pending;
  for (Eigen::Index start = 0; start < n; ++start) {
    if (r(start) != 0) continue;
    r(start) = 1;
    pending.push_back(start);
    while (!pending.empty()) {
      const Eigen::Index i = pending.back();
      pending.pop_back();
      for (Eigen::Index j = 0; j < n; ++j) {
        if (!pattern.couples(i, j) && !pattern.couples(j, i)) continue;
        if (r(j) == r(i)) return std::nullopt;
        if (r(j) == 0) {
          r(j) = -r(i);
          pending.push_back(j);
        }
      }
    }
  }
  return r;
}

}  // namespace bladestab
