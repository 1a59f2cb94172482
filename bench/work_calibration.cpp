// The measured times of the steps every work budget counts, against their counts at
// cli::dense_flops_per_second = 4 Gflop/s, on one core: the calibration of --max-seconds.
//  - a Magnus step (magnus_step_work): a skew-symmetric A₀ (an undamped system's oscillation, the
//    propagator stays bounded), steps of h‖A₀‖₁ = 2, the largest a ladder's safe count allows;
//  - a whole dense eigensolve (whole_eigensolve_flops) of a random positive definite M and K with a
//    skew gyroscopic C, undamped (the Hermitian form) and with 1 % of the identity added (damped).
// Each the median of five runs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

#include <fmt/format.h>

#include "bladestab/ltp/magnus.hpp"
#include "bladestab/modal/modes.hpp"

namespace {

double median_seconds(const std::function<void()>& run) {
  std::vector<double> runs;
  for (int k = 0; k < 5; ++k) {
    const auto start = std::chrono::steady_clock::now();
    run();
    runs.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(runs.begin(), runs.begin() + 2, runs.end());
  return runs[2];
}

void magnus_steps() {
  fmt::print("{:>6} {:>14} {:>18} {:>8}\n", "states", "Magnus step", "magnus_step_work", "ratio");
  for (const Eigen::Index n : {13, 18, 25, 28, 49, 97, 146, 200, 270, 400}) {
    const Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
    Eigen::MatrixXd A = R - R.transpose(), B = Eigen::MatrixXd::Random(n, n);
    const int steps = std::max(8, static_cast<int>(1e9 / (14.0 * n * n * n)));
    A *= 2.0 * steps / A.cwiseAbs().colwise().sum().maxCoeff();
    B /= B.norm();
    const double measured = median_seconds([&] {
      bladestab::magnus_propagator(A, B, [](double t) { return std::sin(t); }, 0, 1, steps);
    }) / steps;
    const double counted = bladestab::magnus_step_work(n) / 4e9;
    fmt::print("{:>6} {:>11.3g} µs {:>15.3g} µs {:>7.2f}×\n", n, measured * 1e6, counted * 1e6, counted / measured);
  }
}

void eigensolves() {
  fmt::print("\n{:>6} {:>8} {:>12} {:>22} {:>8}\n", "dofs", "damped", "eigensolve", "whole_eigensolve_flops", "ratio");
  for (const int n : {48, 100, 170, 250, 400}) {
    const Eigen::MatrixXd P = Eigen::MatrixXd::Random(n, n), Q = Eigen::MatrixXd::Random(n, n),
                          G = Eigen::MatrixXd::Random(n, n);
    bladestab::SecondOrderSystem system;
    system.M = P * P.transpose() + n * Eigen::MatrixXd::Identity(n, n);
    system.K = Q * Q.transpose() + n * Eigen::MatrixXd::Identity(n, n);
    for (const bool damped : {false, true}) {
      system.C = G - G.transpose() + (damped ? 0.01 : 0.0) * Eigen::MatrixXd::Identity(n, n);
      const double measured = median_seconds([&] { bladestab::dense_eigenpairs(system); });
      const double counted = bladestab::whole_eigensolve_flops(n, damped) / 4e9;
      fmt::print("{:>6} {:>8} {:>10.3g} s {:>20.3g} s {:>7.2f}×\n", n, damped ? "yes" : "no", measured, counted,
                 counted / measured);
    }
  }
}

}  // namespace

int main() {
  magnus_steps();
  eigensolves();
}
