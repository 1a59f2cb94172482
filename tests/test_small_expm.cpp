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
