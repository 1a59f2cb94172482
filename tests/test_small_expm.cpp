// SmallExpm against closed forms: the nilpotent shift (whose exponential is the Taylor series
// itself, so every coefficient of the degree-18 scheme is checked), and rotations and shears
// conjugated by a random orthogonal matrix, from ‖X‖ = 1e-3 to 300 (up to 9 squarings).
#include <catch2/catch.hpp>

#include <cmath>

#include <Eigen/Dense>

#include "bladestab/ltp/small_expm.hpp"

using bladestab::SmallExpm;

TEST_CASE("SmallExpm reproduces the Taylor coefficients 1/k! up to k = 18", "[expm]") {
  // J is the 19×19 upper shift: J^19 = 0, so e^{tJ} has t^k/k! on its k-th superdiagonal.
  const int n = 19;
  for (double t : {0.5, 1.0, 3.0}) {  // 3.0 needs two squarings
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i + 1 < n; ++i) J(i, i + 1) = t;
    Eigen::MatrixXd E(n, n);
    SmallExpm(n).compute(J, E);
    double term = 1;
    for (int k = 0; k < n; ++k) {
      INFO("t = " << t << ", k = " << k);
      CHECK(E(0, k) == Approx(term).epsilon(1e-13));
      term *= t / (k + 1);
    }
    CHECK(E.triangularView<Eigen::StrictlyLower>().toDenseMatrix().cwiseAbs().maxCoeff() == 0);
  }
}

TEST_CASE("SmallExpm matches closed forms of rotations and shears over nine decades of norm", "[expm]") {
  // X = Q M Qᵀ with M block diagonal: rotation generators [[0, w], [−w, 0]] (e^M: cos, sin) and
  // shears [[a, b], [0, c]] (e^M: e^a, b (e^a − e^c)/(a − c), e^c); e^X = Q e^M Qᵀ.
  std::srand(7);
  const int blocks = 6, n = 2 * blocks;
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Random(n, n)).householderQ();
  for (double scale : {1e-3, 0.3, 1.0, 2.5, 17.0, 300.0}) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), expM = Eigen::MatrixXd::Zero(n, n);
    for (int b = 0; b < blocks; ++b) {
      const int i = 2 * b;
      const double x = scale * (0.3 + 0.7 * b / (blocks - 1));
      if (b % 2 == 0) {
        M(i, i + 1) = x, M(i + 1, i) = -x;
        expM(i, i) = expM(i + 1, i + 1) = std::cos(x);
        expM(i, i + 1) = std::sin(x), expM(i + 1, i) = -std::sin(x);
      } else {  // decaying shears keep e^M of order one at every scale
        const double a = -x, c = -0.5 * x, s = 0.7 * x;
        M(i, i) = a, M(i + 1, i + 1) = c, M(i, i + 1) = s;
        expM(i, i) = std::exp(a), expM(i + 1, i + 1) = std::exp(c);
        expM(i, i + 1) = s * (std::exp(a) - std::exp(c)) / (a - c);
      }
    }
    Eigen::MatrixXd E(n, n);
    SmallExpm(n).compute(Q * M * Q.transpose(), E);
    const double error = (E - Q * expM * Q.transpose()).norm();
    INFO("‖X‖ scale " << scale << ": error " << error);
    // Squaring s times multiplies the rounding of e^{X/2^s} by up to 2^s (Higham, §10.3).
    CHECK(error <= 1e-14 * std::max(1.0, scale));
  }
}

TEST_CASE("SmallExpm scales by ‖X²‖^½ and ‖X³‖^⅓ where ‖X‖₁ overstates the exponent", "[expm]") {
  // X = [[R, N], [0, R]] with R = [[0, w], [−w, 0]] and N = ν I: R and N commute, so
  // e^X = [[e^R, e^R N], [0, e^R]]. ‖X‖₁ = w + ν, while α₂ = max(‖X²‖^½, ‖X³‖^⅓) ≈ √(2νw) stays
  // far below it (1341 at ν = 1e6: 11 squarings, where ‖X‖₁ would ask for 20 and lose 1.9e-10 of
  // e^X to their rounding; measured 2.4e-13 with α₂).
  for (double nu : {1e-3, 10.0, 1e6}) {
    const double w = 0.9;
    Eigen::Matrix2d R, eR;
    R << 0, w, -w, 0;
    eR << std::cos(w), std::sin(w), -std::sin(w), std::cos(w);
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(4, 4), exact = Eigen::MatrixXd::Zero(4, 4);
    X.topLeftCorner(2, 2) = X.bottomRightCorner(2, 2) = R;
    X.topRightCorner(2, 2) = nu * Eigen::Matrix2d::Identity();
    exact.topLeftCorner(2, 2) = exact.bottomRightCorner(2, 2) = eR;
    exact.topRightCorner(2, 2) = nu * eR;
    Eigen::MatrixXd E(4, 4);
    SmallExpm(4).compute(X, E);
    INFO("ν = " << nu);
    CHECK((E - exact).norm() <= 1e-12 * exact.norm());
  }
}

TEST_CASE("SmallExpm stays finite where X's powers overflow", "[expm]") {
  // ‖X‖ = 1e110: X³ overflows the double range, so the powers are formed again from X/2^s;
  // e^X of this decaying X underflows to zero.
  Eigen::MatrixXd X(2, 2), E(2, 2);
  X << -1e110, 1e109, 0, -2e110;
  SmallExpm(2).compute(X, E);
  CHECK(E.allFinite());
  CHECK(E.cwiseAbs().maxCoeff() == 0);
}
