#pragma once
// RKF45 over one period of ẏ = (A₀ + φ(t) B) y for many columns at once: the monodromy by RKF45
// and the independent checks of a Magnus monodromy (floquet.hpp) integrate with it.
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/ltp/linear_periodic_system.hpp"

namespace bladestab {

// The variation φ of the coefficient and the times where it jumps. Where φ is constant from
// `varies_until` to the period (a pulse's flight), RKF45 stops there and `rest` carries the state
// over the remainder exactly.
struct CoefficientVariation {
  std::function<double(double)> phi;
  std::vector<double> breakpoints;
  double varies_until = 0;  // 0: the whole period
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> rest;
};

// φ = f − f₀ of the system's own series.
CoefficientVariation series_variation(const LinearPeriodicSystem& system);

// X(T) of Ẋ = (A₀ + φ(t) B) X from X(0) by RKF45 at (rtol, atol), landing on the breakpoints (and
// by `rest` after `varies_until`).
Eigen::MatrixXd rkf45_propagate(const LinearPeriodicSystem& system, const CoefficientVariation& variation,
                                const Eigen::MatrixXd& X0, double rtol, double atol);

}  // namespace bladestab
