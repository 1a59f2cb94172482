#pragma once
// The two transient methods (transient.hpp) and what they share: the output times, the samples
// taken from the state [f; ḟ; W], where a run leaves the small-deflection range, and the energy
// norm of the state's change over a revolution.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/transient/exact_stepping.hpp"
#include "bladestab/transient/transient.hpp"
#include "bladestab/transient/transient_system.hpp"
#include "support/work_pool.hpp"

namespace bladestab::detail {

// The samples of a run: tip motion, loads and the energy balance at each output time.
class Recorder {
public:
  Recorder(const BladeModel& model, const TransientSystem& system, double revolution, int samples_per_revolution,
           double revolutions, double initial_energy, double max_lateral_m, double static_tip_axial_m,
           std::vector<TransientSample>& samples);
  // Records the sample at t of the state s = [f; ḟ; W]; where it lies beyond the small-deflection or
  // elastic range, the stop instead (the history ends at the sample before, the last within it).
  std::optional<TransientStop> operator()(double t, const Eigen::VectorXd& s) const;

private:
  // The revolutions at t: the output times lie on the sample grid k/samples_per_revolution of a
  // revolution or at the run's end, so a time on them counts that fraction, not t's rounding.
  double revolutions_at(double t) const;

  const BladeModel& model_;
  const TransientSystem& system_;
  const Eigen::MatrixXd K_E_;
  double revolution_, per_revolution_, run_revolutions_, initial_energy_, max_lateral_m_, static_axial_m_;
  std::vector<TransientSample>& samples_;
};

// The output times of revolution r in [a, b]: evenly spaced, also in a last, partial revolution
// (the spectra assume it); the start only in the first.
std::vector<double> output_times(int r, double a, double b, double revolution, int per_rev);

// √(½Δfᵀ K Δf + ½Δḟᵀ M Δḟ) of a change d = [Δf; Δḟ] (K = K(Ω), positive definite below the
// blade's spin divergence).
double energy_norm(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::VectorXd& d);

// What a run starts from: the revolution's length, the end, the state [f; ḟ; W] (W = 0) and its
// energy; run_start also fills the result's static stretch and initial vibration energy.
struct RunStart {
  double speed = 0, revolution = 0, t_end = 0, initial_energy = 0;
  Eigen::VectorXd x;
  Recorder recorder(const BladeModel& model, const TransientSystem& system, const TransientOptions& options,
                    TransientResult& result) const;
};
RunStart run_start(const BladeModel& model, const Scene& scene, const TransientSystem& system,
                   const TransientOptions& options, TransientResult& result);

// A time the exact stepping lands on, and what happens there.
struct Landing {
  double t = 0;
  bool output = false, whole_revolution = false, check = false;
  bool edge = false;  // a pulse edge or kink: its time is kept exactly when landings merge
};

// Every output time, whole revolution, pulse edge and kink of [0, t_end], and the check time, in
// order; landings closer than 1e-9 of a pulse period (or of a revolution, if that is shorter) are
// one (an output time that falls on a pulse edge up to rounding must not leave a sliver of an
// interval).
std::vector<Landing> landings(const ExactStepper& stepper, const RunStart& begin, const TransientOptions& options,
                              double check_time);

// What the exact-stepping runs do at a landing with the state x = [f; ḟ; W] there.
class LandingLog {
public:
  LandingLog(const BladeModel& model, const TransientSystem& system, const Recorder& record,
             const TransientOptions& options, TransientResult& result, const Eigen::VectorXd& start,
             Eigen::VectorXd& check_state);
  // The check state and the sample; true where the run stops (result.stopped says why).
  bool sample(const Landing& l, double t, const Eigen::VectorXd& x);
  // A whole revolution's change (result.revolution_change) and the progress; true if l is one.
  bool revolution(const Landing& l, const Eigen::VectorXd& x);

private:
  const BladeModel& model_;
  const TransientSystem& system_;
  const Recorder& record_;
  const TransientOptions& options_;
  TransientResult& result_;
  Eigen::VectorXd last_whole_;
  Eigen::VectorXd& check_state_;
  int total_revolutions_;
};

// The change z(T_K) − z(T_{K−1}) of the last whole revolution (`revolution`: its landings, from
// `start`) carried on by that revolution's own propagators, as the linear equations would carry it
// without the small-deflection stop, for growth_continuation revolutions (a multiplier only a
// little above the others, or above a neutral 1, emerges slowly): the logarithm of its energy norm
// after each (growth_continuation.cpp).
std::vector<double> continue_change(ExactStepper& stepper, const Eigen::VectorXd& change, const std::vector<Landing>& revolution,
                             double start);

// Whether every revolution from the `whole`-th whole one on has that revolution's propagators (the
// premise of continue_change): an endless train whose pulse period divides the revolution
// (`revolution` s), or a finite one whose last pulse is over before that revolution starts.
bool revolutions_repeat(const PulseTrain& pulses, double revolution, int whole);

// run_transient by RKF45.
TransientResult run_rkf45_transient(const BladeModel& model, const Scene& scene, const TransientOptions& options);

// run_transient by exact stepping (exact_stepping.hpp); with `check_time` > 0 the state [f; ḟ]
// there is put in `check_state`.
TransientResult run_fast_transient(const BladeModel& model, const Scene& scene, const TransientOptions& options,
                                   double check_time, Eigen::VectorXd& check_state);

// The same in clearance mode (clearance_transient.cpp): free flight exact, each casing contact by
// Runge–Kutta–Fehlberg 7(8), the contact events located on the exact free flight and on the steps.
TransientResult run_fast_clearance_transient(const BladeModel& model, const Scene& scene, const TransientOptions& options,
                                             double check_time, Eigen::VectorXd& check_state);

// The self-check's stretch: through the first contact (at most 0.1 revolution of it) and 0.02
// revolution of what follows, within the run.
double check_stretch(const Scene& scene, const TransientOptions& options);

// The independent integration the self-check compares with (self_check.cpp): its state [f; ḟ] at
// the check's time, its method ("rkf78" or "rkf45") and how long it took. RKF78 polls `stop`
// after each step (WorkCancelled once it is set).
struct ReferenceRun {
  Eigen::VectorXd state;
  std::string method;
};
ReferenceRun reference_run(const BladeModel& model, const Scene& scene, const TransientOptions& options,
                           double check_time, const Cancellation* stop = nullptr);

// The fast history's state at `check_time` against the reference's (SelfCheck).
SelfCheck self_check(const BladeModel& model, const Scene& scene, const TransientOptions& options, double check_time,
                     const Eigen::VectorXd& fast_state, const ReferenceRun& reference);

}  // namespace bladestab::detail
