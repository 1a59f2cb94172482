#include "bladestab/small_expm.hpp"

#include <cmath>

namespace bladestab {
namespace {

constexpr int degree = 12;
// ‖X‖₁ ≤ scaled_norm: the degree-12 remainder is below 0.33¹³/13! ≈ 9e-17.
constexpr double scaled_norm = 0.33;

// 1/k! for k = 0..degree.
struct TaylorCoefficients {
  double c[degree + 1];
  constexpr TaylorCoefficients() : c{} {
    c[0] = 1;
    for (int k = 1; k <= degree; ++k) c[k] = c[k - 1] / k;
  }
};
constexpr TaylorCoefficients taylor{};

}  // namespace

SmallExpm::SmallExpm(Eigen::Index n)
    : x1_(n, n), x2_(n, n), x3_(n, n), x4_(n, n), block_(n, n), product_(n, n) {}

void SmallExpm::compute(const Eigen::MatrixXd& X, Eigen::MatrixXd& result) {
  const double norm = X.cwiseAbs().colwise().sum().maxCoeff();
  const int squarings = norm > scaled_norm ? static_cast<int>(std::ceil(std::log2(norm / scaled_norm))) : 0;
  const double* c = taylor.c;
  x1_ = std::ldexp(1.0, -squarings) * X;
  x2_.noalias() = x1_ * x1_;
  x3_.noalias() = x2_ * x1_;
  x4_.noalias() = x2_ * x2_;
  // p(X) = P₀ + X⁴ (P₁ + X⁴ P₂), P_j = c_{4j} I + c_{4j+1} X + c_{4j+2} X² + c_{4j+3} X³, P₂ += c₁₂ X⁴.
  const auto block = [&](int j, Eigen::MatrixXd& out) {
    out += c[4 * j + 1] * x1_ + c[4 * j + 2] * x2_ + c[4 * j + 3] * x3_;
    out.diagonal().array() += c[4 * j];
  };
  block_ = c[12] * x4_;
  block(2, block_);
  product_.noalias() = x4_ * block_;
  block(1, product_);
  result.noalias() = x4_ * product_;
  block(0, result);
  for (int k = 0; k < squarings; ++k) {
    product_.noalias() = result * result;
    result.swap(product_);
  }
}

}  // namespace bladestab
