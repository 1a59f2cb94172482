#include "bladestab/transient/crosscheck.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <utility>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/transient/response_analysis.hpp"
#include "bladestab/transient/transient.hpp"
#include "bladestab/blade/undamped_modes.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {

// Growth per revolution (TransientResult::growth: the change of the state over each revolution)
// of a transient started 1 µm off the rotating equilibrium in the lowest mode (so a parametric
// instability has a seed), of the linear equations: not stopped at the small-deflection range, the
// friction's direction held however the growing response slides (as in the Floquet system). The
// fast method on the model the Floquet multipliers use (`reduction`), so that the two share its
// basis and reduction and differ in their methods only; the growth from the last revolution change
// carried on for growth_continuation revolutions (transient.hpp).
GrowthFit transient_growth(const BladeModel& model, const Scene& scene, const ReductionSpec& reduction,
                           double revolutions) {
  const double speed = scene.operation.speed_rad_s;
  const int n = model.layout.size();
  Eigen::VectorXd x = rotating_equilibrium(model, speed);
  const Eigen::VectorXd mode = undamped_modes(model, speed, 0, 1).shapes.col(0);
  // A mode without lateral tip motion (an out-of-plane flap of a two-plane blade, docs/theory.md §9)
  // is scaled by its largest coordinate instead.
  const double tip = model.tip_lateral.dot(mode);
  x.head(n) += 1e-6 / (tip != 0 ? tip : mode.cwiseAbs().maxCoeff()) * mode;
  TransientOptions o;
  o.revolutions = revolutions;
  o.tolerance = 1e-8;
  o.initial_state = x;
  o.max_lateral_over_length = HUGE_VAL;
  o.hold_friction_direction = true;
  o.reduction = reduction;
  return run_transient(model, scene, o).growth;
}

}  // namespace

namespace {

// Whether a growth per revolution g ± e and a multiplier per load period ρ ± ε agree: g^(1/n) against
// ρ, its interval the image of [g − e, g + e] under the root (n load periods per revolution).
bool agree_per_load_period(double g, double e, double rho, double rho_error, double n) {
  const double root = std::pow(g, 1 / n), high = std::pow(g + e, 1 / n) - root,
               low = root - std::pow(std::max(g - e, 0.0), 1 / n);
  return std::abs(root - rho) <= std::max(high, low) + rho_error;
}

}  // namespace

bool CrosscheckPoint::cosine_agrees() const {
  return transient_cosine_omitted.empty() &&
         agree_per_load_period(transient_cosine_growth, transient_cosine_error, floquet_cosine, floquet_cosine_error,
                               load_periods_per_revolution);
}

bool CrosscheckPoint::pulse_agrees() const {
  return transient_pulse_omitted.empty() &&
         agree_per_load_period(transient_pulse_growth, transient_pulse_error, floquet_pulse, floquet_pulse_error,
                               load_periods_per_revolution);
}

namespace {

// The paper's cosine approximation (42) as a load: in the time domain the cosine profile over a
// whole load period, which is the same function.
Scene cosine_scene(const Scene& scene) {
  Scene cosine = scene;
  cosine.load.approximation = LoadApproximation::cosine;
  cosine.load.profile = PulseProfile::cosine;
  cosine.load.contact_time_rev = 1 / load_periods_per_revolution(scene);
  return cosine;
}

// The cosine approximation in the frequency domain on the scene's reduction and in the time domain.
void cosine_rows(const BladeModel& model, const Scene& scene, const CrosscheckOptions& o, CrosscheckPoint& p) {
  const Scene cosine = cosine_scene(scene);
  const PeriodicSystem cosine_system = periodic_system(model, cosine, load_series(cosine), scene.model.reduction);
  const FloquetResult fc = floquet_multipliers(cosine_system, {FloquetMethod::automatic, 0, o.tolerance});
  p.cosine_modes = cosine_system.kept_modes;
  p.floquet_cosine = fc.max_abs_multiplier;
  p.floquet_cosine_error = std::max(fc.error_estimate, growth_rounding * fc.max_abs_multiplier);
  const GrowthFit growth = transient_growth(model, cosine, scene.model.reduction, o.revolutions);
  p.transient_cosine_growth = growth.growth;
  p.transient_cosine_error = growth.error_estimate;
  p.transient_cosine_omitted = growth.omitted;
  // Entry by entry Φ(T) converges more slowly than max|ρ| (the stiff modes' phases): RKF45 at
  // 1e-8 and 2048 Magnus steps agree to ~1e-5, where max|ρ| agrees to ~1e-10.
  const Eigen::MatrixXd phi_rkf = rkf45_monodromy(cosine_system, 1e-8);
  const Eigen::MatrixXd phi_magnus = magnus_monodromy(cosine_system, 2048);
  p.rkf45_max_abs_multiplier = Eigen::EigenSolver<Eigen::MatrixXd>(phi_rkf, false).eigenvalues().cwiseAbs().maxCoeff();
  p.monodromy_difference = (phi_rkf - phi_magnus).norm() / phi_magnus.norm();
}

// The scene with its true pulse train (load.approximation = "exact").
Scene exact_train_scene(const Scene& scene) {
  Scene pulse = scene;
  pulse.load.approximation = LoadApproximation::exact;
  return pulse;
}

// The true pulse train's system and the reduction it is built on: the scene's where it names one
// (a kind, or the automatic reduction's vectors), else the whole Ritz model where `stability` takes
// it (true_train_on_whole_model), so that the two commands answer for the same model.
std::pair<PeriodicSystem, ReductionSpec> pulse_system(const BladeModel& model, const Scene& pulse, const PulseTrain& train) {
  const LoadSeries mean = exact_pulse_mean(train);
  const ReductionSpec& r = pulse.model.reduction;
  if (r.kind != ReductionKind::automatic || r.vectors > 0) return {periodic_system(model, pulse, mean, r), r};
  const ReductionSpec whole{ReductionKind::none, 0, 0};
  PeriodicSystem system = periodic_system(model, pulse, mean, whole);
  if (true_train_on_whole_model(system, train)) return {std::move(system), whole};
  return {periodic_system(model, pulse, mean, r), r};
}

// The true pulse train: its multipliers by the monodromy through each contact (pulse_monodromy.hpp,
// as `stability` with load.approximation = "exact" takes them) and its transient, both on
// pulse_system's model. Its Fourier series is left out: on the whole model a series needs the
// Magnus steps of the stiffest mode over the whole period (16,384 a revolution for the paper blade
// at 16 terms, 3 s a point), and on a reduction it can open a tongue the model does not have.
void pulse_rows(const BladeModel& model, const Scene& scene, const CrosscheckOptions& o, CrosscheckPoint& p) {
  const Scene pulse = exact_train_scene(scene);
  const PulseTrain train = pulse_train(pulse);
  const auto [system, reduction] = pulse_system(model, pulse, train);
  const FloquetResult ft = pulse_train_multipliers(system, periodic_pulse(train), {FloquetMethod::monodromy, 0, o.tolerance});
  p.pulse_modes = system.kept_modes;
  p.model_modes = system.all_modes;
  p.floquet_pulse = ft.max_abs_multiplier;
  p.floquet_pulse_error = std::max(ft.error_estimate, growth_rounding * ft.max_abs_multiplier);
  const GrowthFit growth = transient_growth(model, pulse, reduction, o.revolutions);
  p.transient_pulse_growth = growth.growth;
  p.transient_pulse_error = growth.error_estimate;
  p.transient_pulse_omitted = growth.omitted;
}

// The time domain integrates an impulse as a rectangle t_c long, the frequency domain takes its
// jump limit (docs/theory.md §3.2): two loads, where the check compares two methods on one.
void refuse_impulse(const Scene& base) {
  if (base.load.profile != PulseProfile::impulse) return;
  throw InputError("load.profile = \"impulse\": the transients integrate it as a rectangle t_c long and the Floquet "
                   "analysis takes its jump limit, two different loads; crosscheck compares its methods on one: "
                   "give load.profile = \"rectangular\" for the rectangle");
}

// The scene of the point at F̄_max = fbar: a periodic load.
Scene point_scene(const Scene& base, double fbar) {
  Scene scene = base;
  scene.load.fmax_over_fcr = fbar;
  scene.load.pulse_count = 0;
  return scene;
}

// One point of the cross-check at F̄_max = fbar.
CrosscheckPoint crosscheck_point(const BladeModel& model, const Scene& base, double fbar, const CrosscheckOptions& o) {
  CrosscheckPoint p;
  p.fmax_over_fcr = fbar;
  p.load_periods_per_revolution = load_periods_per_revolution(base);
  const Scene scene = point_scene(base, fbar);
  cosine_rows(model, scene, o, p);
  pulse_rows(model, scene, o, p);
  return p;
}

}  // namespace

double load_periods_per_revolution(const Scene& scene) {
  return two_pi / scene.operation.speed_rad_s / pulse_train(scene).period_s;
}

double crosscheck_magnus_work(const Scene& base, const CrosscheckOptions& o) {
  refuse_impulse(base);
  if (o.fmax_over_fcr.empty()) return 0;
  const BladeModel model = assemble_model(base);
  // The systems at the largest load stand for every point's: their steps grow with the load.
  const Scene scene = point_scene(base, *std::max_element(o.fmax_over_fcr.begin(), o.fmax_over_fcr.end()));
  const Scene cosine = cosine_scene(scene);
  const PeriodicSystem c = periodic_system(model, cosine, load_series(cosine), scene.model.reduction);
  // The Floquet ladder and the transient's revolution of contact pieces (each at most twice the safe
  // count), and the 2048-step monodromy compared with RKF45's.
  double work = (2.0 * minimum_magnus_steps(c) * (1 + load_periods_per_revolution(base)) + 2048) *
                magnus_step_work(c.state_size() + 1);
  const Scene pulse = exact_train_scene(scene);
  const PulseTrain train = pulse_train(pulse);
  const PeriodicSystem p = pulse_system(model, pulse, train).first;
  // Its contact, in the Floquet ladder and in the transient.
  work += 4.0 * minimum_magnus_steps(p) * train.contact_time_s / train.period_s * magnus_step_work(p.state_size() + 1);
  return static_cast<double>(o.fmax_over_fcr.size()) * work;
}

std::vector<CrosscheckPoint> crosscheck(const Scene& base, const CrosscheckOptions& o) {
  refuse_impulse(base);
  const BladeModel model = assemble_model(base);
  std::mutex progress_lock;
  int done = 0;
  return run_indexed(o.fmax_over_fcr.size(), o.threads, [&](std::size_t i) {
    CrosscheckPoint p = crosscheck_point(model, base, o.fmax_over_fcr[i], o);
    const std::lock_guard<std::mutex> lock(progress_lock);
    if (o.progress) o.progress(++done, static_cast<int>(o.fmax_over_fcr.size()));
    return p;
  });
}

}  // namespace bladestab
