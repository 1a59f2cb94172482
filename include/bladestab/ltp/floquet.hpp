#pragma once
// Floquet multipliers of the LTP blade (SPEC §4) by three methods:
//  - hill:         Bolotin/Hill harmonic balance, eigenvalues of the Hill matrix in real sin/cos form,
//                  keeping the 2n exponents with the smallest |Im λ| (the classical "sorting");
//  - koopman-hill: Φ(T) ≈ C e^{HT} W (Bayer & Leine 2023), sorting-free;
//  - monodromy:    Φ(T) by the sixth-order Magnus propagator, step count doubled to tolerance;
//  - monodromy-rkf45: Φ(T) by the transient's RKF45 stepper (the time domain's own monodromy),
//                  adaptive at 1e-3 of the tolerance (its global error is ~1e3 rtol) and checked
//                  against one 100 times tighter;
//  - auto:         the monodromy (on a reduced system it is the cheapest and needs no sorting).
// Every result states the method, the truncation and an error estimate, and is reported only after
// checks that do not share its failure mode (FloquetChecks); a failed check raises the fidelity or
// throws NumericalError — never a number.
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"

namespace bladestab {

enum class FloquetMethod { hill, koopman_hill, monodromy, monodromy_rkf45, automatic };
const char* to_string(FloquetMethod);

struct FloquetOptions {
  FloquetMethod method = FloquetMethod::automatic;
  int harmonics = 0;        // q; 0 = raise until the tolerance is met
  double tolerance = 1e-6;  // on max|ρ|, relative once max|ρ| > 1
  // Check the dominant Floquet vector by an independent RKF45 integration (FloquetChecks::residual).
  // Maps leave it to a sample of their points.
  bool independent_check = true;
  // progress(done, total) after each refinement level (a q of the Hill methods, a Magnus step
  // count): `total` is the most levels the refinements may still take, so it overstates; the
  // independent check is the last step, (total, total).
  std::function<void(int, int)> progress = {};
};

// What the result was checked against.
struct FloquetChecks {
  // |det Φ(T) / exp(∫₀ᵀ tr A dt) − 1| (Liouville); NaN where Φ is too ill-conditioned to tell.
  double determinant_error = 0;
  // Undamped (Hamiltonian) systems: multipliers come in pairs ρ, 1/ρ; the largest |ρ ρ_j − 1| over
  // the |ρ| ≥ 1 and their nearest partners. NaN with damping.
  double reciprocal_error = 0;
  // The dominant eigenpair (ρ, v) of Φ(T) checked by integrating v over one period with RKF45:
  // the residual ‖x(T) − ρ v‖ / (|ρ| ‖v‖), and the multiplier that x(T) gives, ρ' = wᴴx(T) / wᴴv
  // with w the left eigenvector, as |ρ' − ρ| / |ρ| (the one checked: the residual also carries
  // errors of Φ that move no multiplier). The true pulse train: RKF45 through the contact, the
  // free flight by the unloaded blade's eigenvectors. NaN for methods that give no Φ(T) (classical
  // Hill) and for stiff unreduced systems (more than 8192 Magnus steps over what RKF45
  // integrates), where it would cost minutes.
  double residual = 0;
  double multiplier_error = 0;
  // Hill methods: max|ρ| of the monodromy on the same system, which they must agree with.
  double monodromy_max_abs_multiplier = 0;
};

struct FloquetResult {
  FloquetMethod method = FloquetMethod::monodromy;  // the one used
  int harmonics = 0;                                // q (Hill methods)
  int steps = 0;                                    // Magnus steps per period (monodromy)
  Eigen::VectorXcd multipliers;                     // ρ, sorted by |ρ|, largest first
  std::vector<std::optional<double>> log_decrements;  // (46) per multiplier; none for real positive ρ
  double max_abs_multiplier = 0;
  double max_real_exponent = 0;                     // ln(max|ρ|)/T
  double error_estimate = 0;                        // of the method on max|ρ| (steps, harmonics)
  bool stable = true;                               // max|ρ| ≤ 1 within the error estimate
  FloquetChecks checks;
};

// The true pulse train (load.approximation = "exact"): Φ(T) by pulse_monodromy.hpp, with the same
// checks (the RKF45 residual integrates the true pulse, landing on its edges).
FloquetResult pulse_train_multipliers(const PeriodicSystem& system, const PulseTrain& train,
                                      const FloquetOptions& options);

// Hill matrix H (SPEC §4): blocks H_jk = A_{j−k} − i k θ δ_jk I, j, k = −q..q.
Eigen::MatrixXcd hill_matrix(const PeriodicSystem& system, int q);

FloquetResult floquet_multipliers(const PeriodicSystem& system, const FloquetOptions& options);

// One method at a fixed truncation, no error estimate (building blocks of the above).
Eigen::VectorXcd hill_multipliers(const PeriodicSystem& system, int q);
Eigen::VectorXcd koopman_hill_multipliers(const PeriodicSystem& system, int q);
Eigen::VectorXcd monodromy_multipliers(const PeriodicSystem& system, int steps);
// Magnus steps per period below which the step's h‖A‖ exceeds 2 (the series would diverge).
int minimum_magnus_steps(const PeriodicSystem& system);
// Largest distance |ρ_a − ρ_b| between two multiplier sets of equal size, each ρ matched to its
// nearest unused partner. Tolerances compare it with tol·max(1, max|ρ|): the small multipliers of
// a strongly unstable Φ carry rounding of order ε‖Φ‖.
double multiplier_set_distance(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b);
// Liouville: |det Φ(T) / exp(∫₀ᵀ tr A dt) − 1|, computed in logarithms.
double liouville_error(const Eigen::MatrixXd& monodromy, const PeriodicSystem& system);
// Φ(T) integrated by RKF45 at relative tolerance `rtol` (all 2n fundamental solutions at once).
Eigen::MatrixXd rkf45_monodromy(const PeriodicSystem& system, double rtol);
// Φ(T) by the Magnus propagator.
Eigen::MatrixXd magnus_monodromy(const PeriodicSystem& system, int steps);

}  // namespace bladestab
