// The time of one Magnus step (ltp/magnus.hpp) on n states, one core, against its count in the work
// budgets (magnus_step_work at cli::dense_flops_per_second = 4 Gflop/s): the calibration of every
// Magnus ladder's work bound and of the CLI's up-front estimates. A skew-symmetric A₀ (an undamped
// system's oscillation: the propagator stays bounded), steps of h‖A₀‖₁ = 2, the largest a ladder's
// safe count allows; as many as take about 0.1 s, the median of five runs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "bladestab/ltp/magnus.hpp"

namespace {

double seconds_per_step(Eigen::Index n) {
  const Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
  Eigen::MatrixXd A = R - R.transpose(), B = Eigen::MatrixXd::Random(n, n);
  const int steps = std::max(8, static_cast<int>(1e9 / (14.0 * n * n * n)));
  A *= 2.0 * steps / A.cwiseAbs().colwise().sum().maxCoeff();
  B /= B.norm();
  std::vector<double> runs;
  for (int k = 0; k < 5; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const Eigen::MatrixXd X = bladestab::magnus_propagator(A, B, [](double t) { return std::sin(t); }, 0, 1, steps);
    runs.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / steps);
    if (!X.allFinite()) fmt::print("n = {}: the propagator overflowed\n", n);
  }
  std::nth_element(runs.begin(), runs.begin() + 2, runs.end());
  return runs[2];
}

}  // namespace

int main() {
  fmt::print("{:>6} {:>14} {:>18} {:>8}\n", "states", "measured", "magnus_step_work", "ratio");
  for (const Eigen::Index n : {13, 18, 25, 28, 49, 97, 146, 200, 270, 400}) {
    const double measured = seconds_per_step(n), counted = bladestab::magnus_step_work(n) / 4e9;
    fmt::print("{:>6} {:>11.3g} µs {:>15.3g} µs {:>7.2f}×\n", n, measured * 1e6, counted * 1e6, counted / measured);
  }
}
