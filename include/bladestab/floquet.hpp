#pragma once
// Floquet multipliers of the LTP blade (SPEC §4) by three methods:
//  - hill:         Bolotin/Hill harmonic balance, eigenvalues of the Hill matrix in real sin/cos form,
//                  keeping the 2n exponents with the smallest |Im λ| (the classical "sorting");
//  - koopman-hill: Φ(T) ≈ C e^{HT} W (Bayer & Leine 2023), sorting-free;
//  - monodromy:    Φ(T) by the sixth-order Magnus propagator, step count doubled to tolerance;
//  - monodromy-rkf45: Φ(T) by the transient's RKF45 stepper (the time domain's own monodromy),
//                  adaptive to the tolerance and checked against one 100 times tighter;
//  - auto:         the cheapest that meets the tolerance.
// Every result states the method, the truncation and an error estimate.
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/periodic_system.hpp"

namespace bladestab {

enum class FloquetMethod { hill, koopman_hill, monodromy, monodromy_rkf45, automatic };
const char* to_string(FloquetMethod);

struct FloquetOptions {
  FloquetMethod method = FloquetMethod::automatic;
  int harmonics = 0;        // q; 0 = raise until the tolerance is met
  double tolerance = 1e-6;  // on max|ρ|, relative once max|ρ| > 1
};

struct FloquetResult {
  FloquetMethod method = FloquetMethod::monodromy;  // the one used
  int harmonics = 0;                                // q (Hill methods)
  int steps = 0;                                    // Magnus steps per period (monodromy)
  Eigen::VectorXcd multipliers;                     // ρ, sorted by |ρ|, largest first
  std::vector<std::optional<double>> log_decrements;  // (46) per multiplier; none for real positive ρ
  double max_abs_multiplier = 0;
  double max_real_exponent = 0;                     // ln(max|ρ|)/T
  double error_estimate = 0;                        // on max|ρ|
  bool stable = true;                               // max|ρ| ≤ 1 within the error estimate
};

// Hill matrix H (SPEC §4): blocks H_jk = A_{j−k} − i k θ δ_jk I, j, k = −q..q.
Eigen::MatrixXcd hill_matrix(const PeriodicSystem& system, int q);

FloquetResult floquet_multipliers(const PeriodicSystem& system, const FloquetOptions& options);

// One method at a fixed truncation, no error estimate (building blocks of the above).
Eigen::VectorXcd hill_multipliers(const PeriodicSystem& system, int q);
Eigen::VectorXcd koopman_hill_multipliers(const PeriodicSystem& system, int q);
Eigen::VectorXcd monodromy_multipliers(const PeriodicSystem& system, int steps);
// Φ(T) integrated by RKF45 at relative tolerance `rtol` (all 2n fundamental solutions at once).
Eigen::MatrixXd rkf45_monodromy(const PeriodicSystem& system, double rtol);
// Φ(T) by the Magnus propagator.
Eigen::MatrixXd magnus_monodromy(const PeriodicSystem& system, int steps);

}  // namespace bladestab
