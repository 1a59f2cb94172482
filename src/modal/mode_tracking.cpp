#include "bladestab/modal/mode_tracking.hpp"

#include <algorithm>

namespace bladestab {

int tracking_candidates(int tracked, int dofs) { return std::min(dofs, tracked + std::max(4, tracked / 2)); }

std::vector<int> assign_by_correlation(const Eigen::MatrixXd& correlation, std::vector<double>& chosen) {
  const Eigen::Index nt = correlation.rows(), nc = correlation.cols();
  std::vector<int> result(nt, -1);
  chosen.assign(nt, 0);
  Eigen::MatrixXd open = correlation;
  for (Eigen::Index step = 0; step < std::min(nt, nc); ++step) {
    Eigen::Index i = 0, j = 0;
    open.maxCoeff(&i, &j);
    result[i] = static_cast<int>(j);
    chosen[i] = correlation(i, j);
    open.row(i).setConstant(-1);
    open.col(j).setConstant(-1);
  }
  return result;
}

Eigen::MatrixXd modal_assurance_matrix(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& b, const Eigen::MatrixXd& M) {
  const Eigen::MatrixXcd Ma = M.cast<std::complex<double>>() * a, Mb = M.cast<std::complex<double>>() * b;
  const Eigen::VectorXd aa = (a.adjoint() * Ma).diagonal().real(), bb = (b.adjoint() * Mb).diagonal().real();
  Eigen::MatrixXd mac = (a.adjoint() * Mb).cwiseAbs2();
  return aa.cwiseInverse().asDiagonal() * mac * bb.cwiseInverse().asDiagonal();
}

}  // namespace bladestab
