#include "bladestab/stability/matrix_export.hpp"

#include <stdexcept>

#include <Eigen/SparseCore>
#include <fmt/format.h>
#include <unsupported/Eigen/SparseExtra>

#include "bladestab/base/input_error.hpp"

namespace bladestab {

ExportedArrays matrix_market_files(const std::string& stem) {
  return {stem + ".A0.mtx", stem + ".B.mtx", stem + ".load.mtx"};
}

ExportedArrays write_matrix_market(const PeriodicSystem& sys, const std::string& stem) {
  return write_matrix_market(sys, matrix_market_files(stem));
}

ExportedArrays write_matrix_market(const PeriodicSystem& sys, const ExportedArrays& files) {
  const auto check = [](bool written, const std::string& file) {
    if (!written) throw InputError(fmt::format("{}: cannot write this file", file));
  };
  const Eigen::SparseMatrix<double> A0 = sys.A0.sparseView(), B = sys.B.sparseView();
  check(Eigen::saveMarket(A0, files.A0), files.A0);
  check(Eigen::saveMarket(B, files.B), files.B);
  const Eigen::VectorXcd load = Eigen::Map<const Eigen::VectorXcd>(sys.coefficients.data(), static_cast<Eigen::Index>(sys.coefficients.size()));
  check(Eigen::saveMarketVector(load, files.load), files.load);
  return files;
}

PeriodicSystem read_matrix_market(const std::string& stem) {
  const ExportedArrays files = matrix_market_files(stem);
  const auto fail = [](const std::string& file) { throw std::runtime_error(fmt::format("{}: cannot read it as Matrix Market", file)); };
  Eigen::SparseMatrix<double> A0, B;
  if (!Eigen::loadMarket(A0, files.A0)) fail(files.A0);
  if (!Eigen::loadMarket(B, files.B)) fail(files.B);
  Eigen::VectorXcd load;
  if (!Eigen::loadMarketVector(load, files.load)) fail(files.load);
  PeriodicSystem sys;
  sys.A0 = Eigen::MatrixXd(A0);
  sys.B = Eigen::MatrixXd(B);
  sys.coefficients.assign(load.data(), load.data() + load.size());
  return sys;
}

}  // namespace bladestab
