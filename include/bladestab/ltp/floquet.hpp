#pragma once
// Floquet multipliers of an LTP system (linear_periodic_system.hpp, docs/theory.md §4):
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
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/ltp/hill.hpp"
#include "bladestab/ltp/linear_periodic_system.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "bladestab/ltp/pulse_monodromy.hpp"

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
  // The most work a Magnus ladder may take, in eigensolver flops (magnus_step_work a step): one not
  // converged where its next level would pass it throws WorkLimitError.
  double max_flops = std::numeric_limits<double>::infinity();
};

// What the result was checked against.
struct FloquetChecks {
  // |det Φ(T) / exp(∫₀ᵀ tr A dt) − 1| (Liouville); NaN where Φ is too ill-conditioned to tell.
  double determinant_error = 0;
  // Systems stated Hamiltonian: multipliers come in pairs ρ, 1/ρ; the largest |ρ ρ_j − 1| over
  // the |ρ| ≥ 1 and their nearest partners. NaN otherwise, and where max|ρ| ≳ 3e5 (the partner of
  // the largest is then below Φ's rounding).
  double reciprocal_error = 0;
  // The dominant eigenpair (ρ, v) of Φ(T) checked by integrating v over one period with RKF45:
  // the residual ‖x(T) − ρ v‖ / (|ρ| ‖v‖), and the multiplier that x(T) gives, ρ' = wᴴx(T) / wᴴv
  // with w the left eigenvector, as |ρ' − ρ| / |ρ| (the one checked: the residual also carries
  // errors of Φ that move no multiplier). A pulsed coefficient: RKF45 through the pulse, the
  // flight after it by the eigenvectors of its constant matrix. NaN for methods that give no Φ(T)
  // (classical Hill) and for stiff systems (more than 8192 Magnus steps over what RKF45
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

// A coefficient that acts in pulses (pulse_monodromy.hpp): Φ(T) through the pulse by Magnus steps
// and the flight after it exactly, with the same checks (the RKF45 check lands on the pulse's edges).
FloquetResult pulse_train_multipliers(const LinearPeriodicSystem& system, const PeriodicPulse& pulse,
                                      const FloquetOptions& options);

FloquetResult floquet_multipliers(const LinearPeriodicSystem& system, const FloquetOptions& options);

}  // namespace bladestab
