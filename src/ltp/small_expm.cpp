#include "bladestab/ltp/small_expm.hpp"

#include <cmath>

#include "bladestab/base/numerical_error.hpp"

namespace bladestab {
namespace {

// ‖X‖₁ up to which T₁₈(X) is e^X to the unit roundoff (Bader, Blanes & Casas 2019, Table 3).
constexpr double theta18 = 1.090863719290036;

// The coefficients of y₁₈ (Bader, Blanes & Casas 2019, eq. (18) and the table after it):
//   A = a1 X + a2 X² + a3 X³,
//   B_k = b0k I + b1k X + b2k X² + b3k X³ + b6k X⁶   (k = 1..4),
//   y₉ = A B₄ + B₃,   y₁₈ = B₁ + (B₂ + y₉) y₉ = T₁₈(X) up to rounding of the coefficients.
constexpr double a1 = -0.100365581030144620014614939405, a2 = -0.00802924648241156960116919515244,
                 a3 = -0.000892138498045729955685466128049;
struct BCoefficients {
  double b0, b1, b2, b3, b6;
};
constexpr BCoefficients B1{0, 0.397849749499645076145196127710, 1.36783778460411719922523706878,
                           0.498289622525382677556858817262, -0.000637898194594723309241550056492};
constexpr BCoefficients B2{-10.9676396052962062593517462675, 1.68015813878906197182785401725,
                           0.0571779846478865512702871713225, -0.00698210122488052084290466483802,
                           0.0000334975017086070538313367340668};
constexpr BCoefficients B3{-0.0904316832390810561971468877018, -0.0676404519071381907560079900380,
                           0.0675961301770459646082799195079, 0.0295552570429315527426069182242,
                           -0.0000139180257516060701124739979344};
constexpr BCoefficients B4{0, 0, -0.0923364619367118592764570775143, -0.0169364939002081717191385115723,
                           -0.0000140086798182036159794363205726};

}  // namespace

SmallExpm::SmallExpm(Eigen::Index n)
    : x1_(n, n), x2_(n, n), x3_(n, n), x6_(n, n), a_(n, n), b_(n, n), y9_(n, n) {}

void SmallExpm::compute(const Eigen::MatrixXd& X, Eigen::MatrixXd& result) {
  const auto norm1 = [](const Eigen::MatrixXd& m) { return m.cwiseAbs().colwise().sum().maxCoeff(); };
  const double norm = norm1(X);
  // A non-finite X would take the squaring count out of int's range; its exponential has no value.
  if (!std::isfinite(norm)) throw NumericalError("the exponential of a non-finite matrix was asked for");
  x2_.noalias() = X * X;
  x3_.noalias() = X * x2_;
  // T₁₈'s backward error is a power series from X¹⁹ on, bounded through α₂ = max(‖X²‖^½, ‖X³‖^⅓)
  // as through ‖X‖ (Al-Mohy & Higham 2009, Thm. 4.2(a), p = 2): far below ‖X‖₁ for the nearly
  // normal generators of a modal Magnus step, whose 1-norm the coupling inflates.
  const double alpha = std::min(norm, std::max(std::sqrt(norm1(x2_)), std::cbrt(norm1(x3_))));
  const int squarings = alpha > theta18 ? static_cast<int>(std::ceil(std::log2(alpha / theta18))) : 0;
  x1_ = std::ldexp(1.0, -squarings) * X;
  if (x3_.allFinite() && 3 * squarings < 1000) {  // scaling by powers of two is exact
    x2_ *= std::ldexp(1.0, -2 * squarings);
    x3_ *= std::ldexp(1.0, -3 * squarings);
  } else {  // X's powers overflowed, or their scale factors would underflow
    x2_.noalias() = x1_ * x1_;
    x3_.noalias() = x1_ * x2_;
  }
  x6_.noalias() = x3_ * x3_;
  const auto combine = [&](const BCoefficients& c, Eigen::MatrixXd& out) {
    out = c.b1 * x1_ + c.b2 * x2_ + c.b3 * x3_ + c.b6 * x6_;
    out.diagonal().array() += c.b0;
  };
  a_ = a1 * x1_ + a2 * x2_ + a3 * x3_;
  combine(B4, b_);
  combine(B3, y9_);
  y9_.noalias() += a_ * b_;  // y₉ = A B₄ + B₃
  combine(B2, b_);
  b_ += y9_;
  combine(B1, result);
  result.noalias() += b_ * y9_;  // y₁₈ = B₁ + (B₂ + y₉) y₉
  for (int k = 0; k < squarings; ++k) {
    a_.noalias() = result * result;
    result.swap(a_);
  }
}

}  // namespace bladestab
