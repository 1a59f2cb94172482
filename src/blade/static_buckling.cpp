#include "bladestab/blade/static_buckling.hpp"

#include <fmt/format.h>

namespace bladestab {

std::optional<double> static_buckling_load(const BladeModel& model, double speed) {
  const Eigen::MatrixXd unloaded = model.elastic_stiffness() + speed * speed * model.K_C1;
  if (Eigen::LLT<Eigen::MatrixXd>(unloaded).info() != Eigen::Success) return std::nullopt;
  // G is positive semi-definite (zero on θ and u), so μ ≥ 0 and the largest one buckles first.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> buckling(model.G, unloaded, Eigen::EigenvaluesOnly);
  return 1 / buckling.eigenvalues().maxCoeff();
}

std::optional<InputError> static_instability(const BladeModel& model, const OperationSpec& operation) {
  const double speed = operation.speed_rad_s;
  if (operation.tip_compression_over_fcr == 0) return std::nullopt;
  if (Eigen::LLT<Eigen::MatrixXd>(model.stiffness(speed)).info() == Eigen::Success) return std::nullopt;
  const double fcr = model.blade.critical_load();
  const std::string key = fmt::format("operation.tip_compression_over_fcr = {}", operation.tip_compression_over_fcr);
  if (const std::optional<double> buckling = static_buckling_load(model, speed)) {
    return InputError(fmt::format("{}: the blade is statically unstable under it at operation.speed_rad_s = {}: it "
                                  "buckles at {:.6g} F_cr ({} basis, {} terms); must be below that",
                                  key, speed, *buckling / fcr, to_string(model.spec.basis), model.spec.terms));
  }
  return InputError(fmt::format("{}: the blade is statically unstable at operation.speed_rad_s = {} even without "
                                "it (spin divergence)",
                                key, speed));
}

}  // namespace bladestab
