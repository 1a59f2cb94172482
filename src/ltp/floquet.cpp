#include "bladestab/ltp/floquet.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "bladestab/ltp/reversing_symmetry.hpp"
#include "bladestab/ltp/step_doubling.hpp"
#include "ltp/monodromy_checks.hpp"

namespace bladestab {
namespace {

using cplx = std::complex<double>;

double max_abs(const Eigen::VectorXcd& rho) { return rho.cwiseAbs().maxCoeff(); }

// ln ρ / T, and (46) δ = −2π Re λ / |Im λ|.
std::optional<double> log_decrement(cplx rho, double T) {
  const cplx lambda = std::log(rho) / T;
  if (lambda.imag() == 0) return std::nullopt;
  return -two_pi * lambda.real() / std::abs(lambda.imag());
}

struct Attempt {
  Eigen::VectorXcd multipliers;
  double error = 0;
  int harmonics = 0, steps = 0;
  Eigen::MatrixXd monodromy;  // Φ(T), where the method has one
};

// Counts refinement levels for FloquetOptions::progress. plan(n): at most n more levels (and the
// stages after them) from here.
class LevelCounter {
public:
  explicit LevelCounter(const std::function<void(int, int)>& progress) : progress_(progress) {}
  void plan(int levels) { planned_ = std::max(levels, 1); }
  void level_done() {
    ++done_, planned_ = std::max(planned_ - 1, 1);
    if (progress_) progress_(done_, done_ + planned_);
  }
  void finished() {
    if (progress_) progress_(done_, done_);
  }

private:
  const std::function<void(int, int)>& progress_;
  int done_ = 0, planned_ = 1;
};

// The harmonic levels q = start, start + 2, … that refine_harmonics may take.
int harmonic_levels(const LinearPeriodicSystem& sys, int start, int max_q, int max_size) {
  int levels = 0;
  for (int q = start; q <= max_q && sys.state_size() * (2 * q + 1) <= max_size; q += 2) ++levels;
  return levels;
}

// Raises q by 2 from `start` until the whole multiplier sets of two successive truncations agree
// within tol, the Hill matrix would exceed `max_size` rows, or q passes `max_q`. Returns whether
// the tolerance was met; `out` holds the last truncation either way.
template <class Method>
bool refine_harmonics(const LinearPeriodicSystem& sys, Method method, int start, int max_q, int max_size, double tol,
                      Attempt& out, LevelCounter& counter) {
  const int levels = harmonic_levels(sys, start, max_q, max_size);
  counter.plan(levels + 1);  // and the monodromy the result is checked against
  Eigen::VectorXcd previous = method(sys, std::max(start - 2, 1));
  for (int level = 0, q = start; level < levels; ++level, q += 2) {
    const Eigen::VectorXcd current = method(sys, q);
    counter.level_done();
    out = {current, multiplier_set_distance(current, previous), q, 0, {}};
    if (out.error <= tol * std::max(1.0, max_abs(current))) return true;
    previous = current;
  }
  return false;
}

// Why a period needs more than max_magnus_steps steps (h‖A‖ ≤ 2 asks ‖A‖T/2 of them): in modal
// form, either the period is too long even for the slowest mode (pulses too slow for a Floquet
// analysis: a speed range from 0 to 1e-300 rad/s gives θ ≈ 5e-307 rad/s) or the stiffest mode is
// stiffer than the period takes.
NumericalError too_many_steps(const LinearPeriodicSystem& sys) {
  const std::string need = fmt::format("the monodromy needs more than {} Magnus steps per period 2π/θ = {:.3g} s "
                                       "(θ = {:.3g} rad/s)", max_magnus_steps, sys.period(), sys.angular_frequency);
  if (!sys.modal) {
    return NumericalError(fmt::format("{} for this {}-state system: its stiffest rates need a modal reduction", need,
                                      sys.state_size()));
  }
  const Eigen::VectorXd omega = sys.modal->frequencies();
  if (omega.minCoeff() * sys.period() / 2 > max_magnus_steps) {
    return NumericalError(fmt::format("{} even for the slowest mode, {:.3g} rad/s: the period is too long for a "
                                      "Floquet analysis; raise the pulse frequency", need, omega.minCoeff()));
  }
  return NumericalError(fmt::format("{}: the system has {} modes, the stiffest at {:.3g} rad/s; keep fewer (a modal "
                                    "cut-off below it, or fewer reduction vectors)", need, omega.size(), omega.maxCoeff()));
}

// Doubles the Magnus steps from 1/64 of the count where h‖A‖ ≤ 2 until StepDoubling accepts the
// multiplier sets (on the paper blade 128 steps are within 1e-8 where that condition asks for
// 512: the exponential takes A₀'s stiff modes exactly). A level that overflows restarts the
// ladder's evidence (StepDoubling::overflowed). The levels stop where `max_flops` would be passed.
// A ladder over half the period (magnus_monodromy) not settled past the safe count is taken to
// sit at a Jordan pair, where the rounding of U⁻¹ leaves the pair a floor of √(ε cond U): it goes
// on over the whole period, from the level before taken again over the whole period: a ladder of
// its own, counting whole steps in the work left.
Attempt refine_steps(const LinearPeriodicSystem& sys, double tol, double max_flops, LevelCounter& counter) {
  const int safe = minimum_magnus_steps(sys);
  if (safe > max_magnus_steps) throw too_many_steps(sys);
  const double whole_step = magnus_step_work(sys.state_size()), level_step = monodromy_step_work(sys);
  StepDoubling ladder(std::max(8, safe / 64), max_magnus_steps, safe, level_step, max_flops);
  counter.plan(ladder.levels() + 1);  // and the checks after
  Eigen::VectorXcd previous;
  bool whole_period = !reversing_signature(sys);
  double spent = 0;
  for (int steps = ladder.first(); steps <= ladder.last(); steps *= 2) {
    if (!whole_period && steps > safe && previous.size() > 0) {
      whole_period = true;
      ladder = StepDoubling(steps / 2, max_magnus_steps, safe, whole_step, max_flops - spent);
      if (ladder.last() < steps) break;
      counter.plan(ladder.levels() + 1);
      previous = sorted_eigenvalues(magnus_monodromy(sys, steps / 2, true));
      spent += steps / 2 * whole_step;
      counter.level_done();
    }
    Eigen::MatrixXd phi = magnus_monodromy(sys, steps, whole_period);
    spent += steps * (whole_period ? whole_step : level_step);
    counter.level_done();
    if (!phi.allFinite()) {
      if (ladder.overflowed(steps)) throw monodromy_overflow(sys.period());
      previous.resize(0);
      continue;
    }
    const Eigen::VectorXcd current = sorted_eigenvalues(phi);
    if (previous.size() == current.size()) {
      const double scale = std::max(1.0, max_abs(current));
      // Not below the rounding of Φ's eigenvalues: an estimate of 0 would claim more than is known.
      const std::optional<double> error =
          ladder.judge(steps, multiplier_set_distance(current, previous), tol * scale, 1e-14 * scale);
      if (error) return {current, *error, 0, steps, phi};
    }
    previous = current;
  }
  ladder.give_up(fmt::format("the monodromy matrix did not converge to {:g}", tol), "Magnus steps per period");
}

FloquetResult result_of(FloquetMethod method, const Attempt& attempt, const FloquetChecks& checks, double period) {
  FloquetResult result;
  result.method = method;
  result.harmonics = attempt.harmonics;
  result.steps = attempt.steps;
  result.multipliers = attempt.multipliers;
  result.error_estimate = attempt.error;
  result.checks = checks;
  result.max_abs_multiplier = max_abs(attempt.multipliers);
  result.max_real_exponent = std::log(result.max_abs_multiplier) / period;
  result.stable = result.max_abs_multiplier <= 1 + std::max(attempt.error, 1e-9);
  for (Eigen::Index k = 0; k < attempt.multipliers.size(); ++k) {
    result.log_decrements.push_back(log_decrement(attempt.multipliers(k), period));
  }
  return result;
}

}  // namespace

const char* to_string(FloquetMethod m) {
  switch (m) {
    case FloquetMethod::hill: return "hill";
    case FloquetMethod::koopman_hill: return "koopman-hill";
    case FloquetMethod::monodromy: return "monodromy";
    case FloquetMethod::monodromy_rkf45: return "monodromy-rkf45";
    case FloquetMethod::automatic: return "auto";
  }
  return "?";
}

FloquetResult floquet_multipliers(const LinearPeriodicSystem& sys, const FloquetOptions& options) {
  const double tol = options.tolerance;
  const int q = options.harmonics;
  constexpr int max_q = 40, max_hill_rows = 1200;
  Attempt attempt;
  FloquetChecks checks;
  LevelCounter counter(options.progress);
  switch (options.method) {
    case FloquetMethod::hill:
    case FloquetMethod::koopman_hill: {
      const auto method = options.method == FloquetMethod::hill ? hill_multipliers : koopman_hill_multipliers;
      if (q > 0) {
        // A given q is held to the refinement's own limit: the dense Hill matrix's eigensolve grows
        // like rows³ (q = 60 on the paper blade's 24 states: 2904 rows, most of an hour).
        const int rows = sys.state_size() * (2 * q + 1);
        if (rows > max_hill_rows) {
          throw ParameterError("harmonics", fmt::format("{}: the Hill matrix would have {} rows ({} states × {} harmonics), "
                                       "beyond the {} its methods are held to; use fewer harmonics or the monodromy method",
                                       q, rows, sys.state_size(), 2 * q + 1, max_hill_rows));
        }
        const Eigen::VectorXcd current = method(sys, q), coarser = method(sys, std::max(1, q - 2));
        attempt = {current, multiplier_set_distance(current, coarser), q, 0, {}};
      } else if (!refine_harmonics(sys, method, 2, max_q, max_hill_rows, tol, attempt, counter)) {
        throw NumericalError(fmt::format("{}: the multipliers did not settle to {:g} up to q = {} ({} rows); use "
                                         "the monodromy method", to_string(options.method), tol, attempt.harmonics,
                                         sys.state_size() * (2 * attempt.harmonics + 1)));
      }
      // The kept exponents must agree with the monodromy's (sorting can pick wrong ones).
      const Attempt reference = refine_steps(sys, tol, options.max_flops, counter);
      checks = check_monodromy(reference.monodromy, reference.multipliers, sys, tol, false, series_variation(sys));
      const double disagreement = std::abs(max_abs(attempt.multipliers) - max_abs(reference.multipliers));
      if (disagreement > attempt.error + reference.error + tol * std::max(1.0, max_abs(reference.multipliers))) {
        throw NumericalError(fmt::format("{} (q = {}): max|ρ| = {:.8g} disagrees with the monodromy's {:.8g}{}; use "
                                         "the monodromy method", to_string(options.method), attempt.harmonics,
                                         max_abs(attempt.multipliers), max_abs(reference.multipliers),
                                         options.method == FloquetMethod::hill
                                             ? " (the classical sorting kept the wrong exponents)"
                                             : ""));
      }
      break;
    }
    case FloquetMethod::monodromy:
    case FloquetMethod::automatic:
      attempt = refine_steps(sys, tol, options.max_flops, counter);
      checks = check_monodromy(attempt.monodromy, attempt.multipliers, sys, tol, options.independent_check,
                               series_variation(sys));
      break;
    case FloquetMethod::monodromy_rkf45: {
      // RKF45's global error over a period's many oscillations is ~1e3 rtol (measured on the paper
      // blade: 600 rtol in the multipliers, 1300 rtol in det Φ): the loose run at tol·1e-3 meets tol,
      // and the distance to the tight one, 100 times finer, is its error estimate.
      const Eigen::MatrixXd tight = rkf45_monodromy(sys, tol * 1e-5), loose = rkf45_monodromy(sys, tol * 1e-3);
      if (!tight.allFinite() || !loose.allFinite()) throw NumericalError("the RKF45 monodromy overflowed");
      const Eigen::VectorXcd rho = sorted_eigenvalues(tight);
      attempt = {rho, multiplier_set_distance(rho, sorted_eigenvalues(loose)), 0, 0, tight};
      checks = check_monodromy(tight, rho, sys, tol, options.independent_check, series_variation(sys));
      break;
    }
  }
  counter.finished();
  return result_of(options.method == FloquetMethod::automatic ? FloquetMethod::monodromy : options.method, attempt,
                   checks, sys.period());
}

FloquetResult pulse_train_multipliers(const LinearPeriodicSystem& sys, const PeriodicPulse& pulse,
                                      const FloquetOptions& options) {
  const PulseMonodromy p = exact_pulse_monodromy(sys, pulse, options.tolerance, options.progress, options.max_flops);
  const Attempt attempt{p.multipliers, p.error_estimate, 0, p.steps, p.monodromy};
  const CoefficientVariation variation =
      options.independent_check ? pulse_check_variation(sys, pulse) : CoefficientVariation{};
  return result_of(FloquetMethod::monodromy, attempt,
                   check_monodromy(p.monodromy, p.multipliers, sys, options.tolerance, options.independent_check,
                                   variation),
                   sys.period());
}

}  // namespace bladestab
