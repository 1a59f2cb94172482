// The transient benchmark's integrators side by side on one system (bench/run; built only with
// -DBLADESTAB_BENCH=ON): the blade's response to its tip-load pulse train, x = [f; ḟ; W], the
// equations run_transient integrates (TransientSystem, transient_system.hpp), for load.mode = "force"
// without friction or follower (the right-hand side is then smooth between the pulse edges, where
// F or F' jumps). Every integrator stops exactly on each pulse edge and each whole revolution:
//
//   rkf45          bladestab's RKF45 (rkf45_integrate), adaptive, with run_transient's cap on the step
//   rkf45-fixed    bladestab's RKF45 at run_transient's fixed step (one point, no tolerance)
//   odeint-dopri5  Boost.Odeint, controlled runge_kutta_dopri5
//   odeint-rkf78   Boost.Odeint, controlled runge_kutta_fehlberg78
//   arkode-rkf45   SUNDIALS ARKODE ERKStep, Fehlberg 6-4-5 (the same pair as ours)
//   arkode-dopri5  SUNDIALS ARKODE ERKStep, Dormand–Prince 7-4-5
//   fast           bladestab's exact stepping (run_transient's fast method, exact_stepping.hpp) at
//                  --tolerance rtol, without its RKF45 self-check, 8 samples per revolution
//
// at rtol from --rtol and atol = rtol · 1e-6 (run_transient's absolute floor). The error of a run is
// measured at the whole revolutions against a reference (odeint-rkf78 at --reference-rtol): the
// largest tip deflection difference, lateral relative to the reference's lateral peak and axial
// relative to its axial vibration peak (about the rotating equilibrium), whichever is larger.
// One JSON object per line: integrator, rtol, atol, times_s, median_s, error, steps, evaluations.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <boost/numeric/odeint.hpp>
#include <fmt/format.h>

#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include "support/blas_threads.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/ltp/rkf45.hpp"
#include "bladestab/scene/scene.hpp"
#include "bladestab/transient/transient.hpp"
#include "bladestab/transient/transient_system.hpp"

namespace {

using namespace bladestab;
constexpr double two_pi = 6.28318530717958647692;

struct Problem {
  Problem(const Scene& scene, const BladeModel& model, int revolutions);

  Scene scene;
  BladeModel model;
  int n = 0;                 // dofs; the state has 2n + 1 entries
  double revolution_s = 0;   // one revolution
  int revolutions = 0;
  TransientSystem system;
  Eigen::RowVectorXd tip_lateral, tip_axial;
  Eigen::VectorXd start;     // [equilibrium; 0; 0]
  double max_step_s = 0, fixed_step_s = 0;
  std::vector<double> stops; // pulse edges and whole revolutions, increasing, ending at the last revolution

  const PulseTrain& pulses() const { return system.pulses(); }
  void rhs(double t, const double* x, double* dx) const {
    Eigen::Map<Eigen::VectorXd> derivative(dx, 2 * n + 1);
    system.derivative(t, Eigen::Map<const Eigen::VectorXd>(x, 2 * n + 1), derivative);
  }
};

Problem::Problem(const Scene& scene, const BladeModel& model, int revolutions)
    : scene(scene), model(model), n(model.layout.size()), revolution_s(two_pi / scene.operation.speed_rad_s), revolutions(revolutions),
      system(model, scene, TransientOptions{}), tip_lateral(model.tip_lateral), tip_axial(model.tip_axial) {
  const double speed = scene.operation.speed_rad_s;
  start = Eigen::VectorXd::Zero(2 * n + 1);
  start.head(2 * n) = rotating_equilibrium(model, speed);
  const double t_end = revolutions * revolution_s;
  fixed_step_s = max_step_s = choose_fixed_step(model.stiffness(speed), model.M, t_end).step_s;  // as run_transient
  stops = pulses().edges(0, t_end);
  for (int r = 1; r <= revolutions; ++r) stops.push_back(r * revolution_s);
  std::sort(stops.begin(), stops.end());
  stops.erase(std::remove_if(stops.begin(), stops.end(), [&](double t) { return t <= 0 || t > t_end; }), stops.end());
  stops.erase(std::unique(stops.begin(), stops.end()), stops.end());
}

Problem make_problem(const Scene& scene, int revolutions) {
  if (scene.load.mode != LoadMode::force || scene.load.friction != 0) {
    throw std::runtime_error("transient_peers: the benchmark's system is load.mode = \"force\" without friction");
  }
  return Problem(scene, assemble_model(scene), revolutions);
}

struct Run {
  std::vector<Eigen::VectorXd> at_revolutions;  // the state at each whole revolution
  long steps = 0, evaluations = 0;
};



bool is_revolution(const Problem& p, double t) {
  const double r = t / p.revolution_s;
  return std::abs(r - std::round(r)) < 1e-12 * std::max(1.0, r);
}

// The fast method: its samples at the whole revolutions as states whose f carries the sampled tip
// deflections (the least-norm f with those tip values: only they are compared).
Run run_fast(const Problem& p, double rtol) {
  TransientOptions o;
  o.revolutions = p.revolutions;
  o.tolerance = o.contact_tolerance = rtol;
  o.self_check = false;
  o.samples_per_revolution = 8;
  o.max_lateral_over_length = HUGE_VAL;
  const TransientResult r = run_transient(p.model, p.scene, o);
  if (r.method != TransientMethod::fast) throw std::runtime_error("fast: not applicable: " + r.fallback);
  Eigen::MatrixXd tips(2, p.n);
  tips << p.tip_lateral, p.tip_axial;
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> least_norm(tips);
  Run run;
  for (const TransientSample& s : r.samples) {
    if (s.time_s == 0 || !is_revolution(p, s.time_s)) continue;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * p.n + 1);
    x.head(p.n) = least_norm.solve(Eigen::Vector2d(s.tip_lateral_m, s.tip_axial_m));
    run.at_revolutions.push_back(x);
  }
  run.steps = r.exact.magnus_steps + r.exact.intervals;
  return run;
}

// bladestab's RKF45, one revolution per call as run_transient does, landing on the pulse edges.
Run run_rkf45(const Problem& p, double rtol, bool adaptive) {
  const OdeFunction f = [&p](double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    dx.resize(x.size());
    p.rhs(t, x.data(), dx.data());
  };
  StepControl control;
  control.adaptive = adaptive;
  control.rtol = rtol;
  control.atol = rtol * 1e-6;
  (adaptive ? control.max_step : control.fixed_step) = p.max_step_s;
  Run run;
  Eigen::VectorXd x = p.start;
  for (int r = 0; r < p.revolutions; ++r) {
    const double a = r * p.revolution_s, b = (r + 1) * p.revolution_s;
    const StepStatistics s = rkf45_integrate(f, x, a, b, control, p.pulses().edges(a, b), {}, {});
    run.steps += s.accepted + s.rejected;
    run.evaluations += s.evaluations;
    run.at_revolutions.push_back(x);
  }
  return run;
}

// Boost.Odeint: a controlled stepper stepped by hand between the stops, keeping its step size.
template <class Stepper>
Run run_odeint(const Problem& p, double rtol) {
  namespace odeint = boost::numeric::odeint;
  using State = std::vector<double>;
  auto stepper = odeint::make_controlled(rtol * 1e-6, rtol, Stepper());
  long evaluations = 0;
  const auto system = [&](const State& x, State& dx, double t) {
    ++evaluations;
    dx.resize(x.size());
    p.rhs(t, x.data(), dx.data());
  };
  Run run;
  State x(p.start.data(), p.start.data() + p.start.size());
  double t = 0, dt = p.max_step_s;
  for (double stop : p.stops) {
    while (t < stop) {
      double h = std::min(dt, stop - t);
      const bool clipped = h < dt;
      const bool accepted = stepper.try_step(system, x, t, h) == odeint::success;  // t += h on success; h: next
      ++run.steps;
      if (accepted && clipped && std::abs(t - stop) <= 1e-14 * stop) t = stop;
      dt = accepted && clipped ? std::max(dt, h) : h;  // a step clipped to land keeps the step it had
      if (dt < 1e-16) throw std::runtime_error("odeint: step size underflow");
    }
    if (is_revolution(p, stop)) run.at_revolutions.push_back(Eigen::Map<const Eigen::VectorXd>(x.data(), x.size()));
  }
  run.evaluations = evaluations;
  return run;
}

// SUNDIALS ARKODE's explicit stepper with a given Butcher table, stopping exactly at each stop.
Run run_arkode(const Problem& p, double rtol, ARKODE_ERKTableID table) {
  SUNContext context = nullptr;
  if (SUNContext_Create(nullptr, &context) != 0) throw std::runtime_error("SUNContext_Create failed");
  const int size = static_cast<int>(p.start.size());
  N_Vector y = N_VNew_Serial(size, context);
  N_VEnableFusedOps_Serial(y, SUNTRUE);  // one pass per stage combination instead of one per term
  std::copy(p.start.data(), p.start.data() + size, N_VGetArrayPointer(y));
  const ARKRhsFn f = [](realtype t, N_Vector x, N_Vector dx, void* data) {
    static_cast<const Problem*>(data)->rhs(t, N_VGetArrayPointer(x), N_VGetArrayPointer(dx));
    return 0;
  };
  void* mem = ERKStepCreate(f, 0.0, y, context);
  const auto ok = [](int flag, const char* what) {
    if (flag < 0) throw std::runtime_error(fmt::format("ARKODE {} failed: {}", what, flag));
  };
  ok(ERKStepSetUserData(mem, const_cast<Problem*>(&p)), "SetUserData");
  ok(ERKStepSStolerances(mem, rtol, rtol * 1e-6), "SStolerances");
  ok(ERKStepSetTableNum(mem, table), "SetTableNum");
  ok(ERKStepSetMaxNumSteps(mem, -1), "SetMaxNumSteps");  // unlimited
  Run run;
  double t = 0;
  for (double stop : p.stops) {
    ok(ERKStepSetStopTime(mem, stop), "SetStopTime");
    ok(ERKStepEvolve(mem, stop, y, &t, ARK_NORMAL), "Evolve");
    if (is_revolution(p, stop)) run.at_revolutions.push_back(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), size));
  }
  long steps = 0, failures = 0, evaluations = 0;
  ERKStepGetNumSteps(mem, &steps);
  ERKStepGetNumErrTestFails(mem, &failures);
  ERKStepGetNumRhsEvals(mem, &evaluations);
  run.steps = steps + failures;
  run.evaluations = evaluations;
  ERKStepFree(&mem);
  N_VDestroy(y);
  SUNContext_Free(&context);
  return run;
}

Run run_integrator(const Problem& p, const std::string& name, double rtol) {
  namespace odeint = boost::numeric::odeint;
  using State = std::vector<double>;
  if (name == "rkf45") return run_rkf45(p, rtol, true);
  if (name == "fast") return run_fast(p, rtol);
  if (name == "rkf45-fixed") return run_rkf45(p, rtol, false);
  if (name == "odeint-dopri5") return run_odeint<odeint::runge_kutta_dopri5<State>>(p, rtol);
  if (name == "odeint-rkf78") return run_odeint<odeint::runge_kutta_fehlberg78<State>>(p, rtol);
  if (name == "arkode-rkf45") return run_arkode(p, rtol, ARKODE_FEHLBERG_6_4_5);
  if (name == "arkode-dopri5") return run_arkode(p, rtol, ARKODE_DORMAND_PRINCE_7_4_5);
  throw std::runtime_error("unknown integrator " + name);
}

// Largest tip deflection difference at the whole revolutions: lateral over the reference's lateral
// peak, axial over its axial vibration peak about the equilibrium.
double tip_error(const Problem& p, const Run& run, const Run& reference) {
  const int n = p.n;
  const double lat_eq = p.tip_lateral.dot(p.start.head(n)), ax_eq = p.tip_axial.dot(p.start.head(n));
  double lat_peak = 0, ax_peak = 0, lat_err = 0, ax_err = 0;
  for (std::size_t k = 0; k < reference.at_revolutions.size(); ++k) {
    const Eigen::VectorXd& r = reference.at_revolutions[k];
    lat_peak = std::max(lat_peak, std::abs(p.tip_lateral.dot(r.head(n)) - lat_eq));
    ax_peak = std::max(ax_peak, std::abs(p.tip_axial.dot(r.head(n)) - ax_eq));
    if (k >= run.at_revolutions.size()) return INFINITY;
    const Eigen::VectorXd d = run.at_revolutions[k].head(n) - r.head(n);
    lat_err = std::max(lat_err, std::abs(p.tip_lateral.dot(d)));
    ax_err = std::max(ax_err, std::abs(p.tip_axial.dot(d)));
  }
  const double e = std::max(lat_err / lat_peak, ax_err / ax_peak);
  return std::isfinite(e) ? e : INFINITY;
}

std::string json_number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "null"; }

// The scene's transient equations for bench/scipy_transient.py, every matrix premultiplied by M⁻¹
// as TransientSystem does: f̈ = c − K f − C ḟ + F(t) (p_u − G f) + μ F(t) cos β · p_v (the friction
// with its sign fixed: the tip slides at ΩR), F(t) the half-sine train. JSON, 17 digits.
void export_system(const Scene& scene, const BladeModel& model, const std::string& path) {
  const double speed = scene.operation.speed_rad_s;
  const Eigen::LLT<Eigen::MatrixXd> mass(model.M);
  const Eigen::MatrixXd C = damping_matrix(model, scene.damping, speed) + model.gyroscopic(speed);
  const PulseTrain pulses = pulse_train(scene);
  if (pulses.profile != PulseProfile::half_sine) throw std::runtime_error("--export-system: half-sine pulses only");
  const auto matrix = [](const Eigen::MatrixXd& a) {
    std::vector<std::string> rows;
    for (Eigen::Index i = 0; i < a.rows(); ++i) rows.push_back(fmt::format("[{:.17g}]", fmt::join(a.row(i), ", ")));
    return fmt::format("[{}]", fmt::join(rows, ", "));
  };
  const Eigen::VectorXd friction = scene.load.friction * std::cos(model.blade.beta_rad) * model.tip_lateral.transpose();
  std::ofstream out(path);
  out << fmt::format(
      "{{\"n\": {}, \"K\": {}, \"C\": {}, \"G\": {}, \"c\": {}, \"p_u\": {}, \"p_friction\": {}, "
      "\"equilibrium\": {}, \"tip_lateral\": {}, \"peak_n\": {:.17g}, \"contact_s\": {:.17g}, \"period_s\": {:.17g}, "
      "\"revolution_s\": {:.17g}}}\n",
      model.layout.size(), matrix(mass.solve(model.stiffness(speed))), matrix(mass.solve(C)), matrix(mass.solve(model.G)),
      matrix(mass.solve(model.steady_load(speed)).transpose()),
      matrix(mass.solve(Eigen::VectorXd(model.tip_axial.transpose())).transpose()),
      matrix(mass.solve(friction).transpose()), matrix(rotating_equilibrium(model, speed).transpose()),
      matrix(model.tip_lateral), pulses.peak_n, pulses.contact_time_s, pulses.period_s, two_pi / speed);
}

}  // namespace

int main(int argc, char** argv) {
  use_single_threaded_blas();  // as the program does
  CLI::App app{"transient integrators side by side on the blade's pulse-train response (bench/run)"};
  std::string scene_path;
  std::vector<std::string> overrides;
  std::vector<std::string> integrators{"fast", "rkf45", "rkf45-fixed", "odeint-dopri5", "odeint-rkf78", "arkode-rkf45", "arkode-dopri5"};
  std::vector<double> tolerances{1e-5, 1e-7, 1e-9};
  int revolutions = 10, repeats = 5;
  double reference_rtol = 1e-13, budget_s = 1e300;
  app.add_option("scene", scene_path)->required();
  app.add_option("--set", overrides);
  app.add_option("--integrators", integrators)->delimiter(',');
  app.add_option("--rtol", tolerances)->delimiter(',');
  app.add_option("--revolutions", revolutions);
  app.add_option("--repeats", repeats);
  app.add_option("--budget-s", budget_s, "fewer repeats (at least 1) where the repeats of one run would take longer");
  app.add_option("--reference-rtol", reference_rtol);
  std::string export_path;
  app.add_option("--export-system", export_path, "write the equations for bench/scipy_transient.py and stop");
  CLI11_PARSE(app, argc, argv);
  try {
    const Scene scene = load_scene(scene_path, overrides);
    if (!export_path.empty()) {
      export_system(scene, assemble_model(scene), export_path);
      return 0;
    }
    const Problem p = make_problem(scene, revolutions);
    const auto clock = [] { return std::chrono::steady_clock::now(); };
    const auto t0 = clock();
    const Run reference = run_integrator(p, "odeint-rkf78", reference_rtol);
    const double reference_s = std::chrono::duration<double>(clock() - t0).count();
    // The reference's own error: against the same at 10× the tolerance.
    const Run coarser = run_integrator(p, "odeint-rkf78", 10 * reference_rtol);
    // Its tip deflections at the whole revolutions, so bench/run can measure `bladestab transient` too.
    std::vector<std::string> lateral, axial;
    for (const Eigen::VectorXd& x : reference.at_revolutions) {
      lateral.push_back(fmt::format("{}", p.tip_lateral.dot(x.head(p.n))));
      axial.push_back(fmt::format("{}", p.tip_axial.dot(x.head(p.n))));
    }
    std::cout << fmt::format(
        "{{\"reference\": \"odeint-rkf78\", \"rtol\": {}, \"time_s\": {:.4g}, \"difference_to_10x_rtol\": {}, "
        "\"states\": {}, \"revolutions\": {}, \"max_step_s\": {:.6g}, \"pulse_edges_and_revolutions\": {}, "
        "\"equilibrium_tip_lateral_m\": {}, \"equilibrium_tip_axial_m\": {}, \"tip_lateral_m\": [{}], "
        "\"tip_axial_m\": [{}]}}\n",
        reference_rtol, reference_s, json_number(tip_error(p, coarser, reference)), 2 * p.n + 1, revolutions,
        p.max_step_s, p.stops.size(), p.tip_lateral.dot(p.start.head(p.n)), p.tip_axial.dot(p.start.head(p.n)),
        fmt::join(lateral, ", "), fmt::join(axial, ", ")) << std::flush;
    for (const std::string& name : integrators) {
      const std::vector<double> rtols = name == "rkf45-fixed" ? std::vector<double>{1e-8} : tolerances;
      for (double rtol : rtols) {
        std::vector<double> times;
        Run run;
        for (int k = 0; k < repeats; ++k) {
          const auto start = clock();
          run = run_integrator(p, name, rtol);
          times.push_back(std::chrono::duration<double>(clock() - start).count());
          double sum = 0;
          for (double s : times) sum += s;
          if (sum / times.size() * repeats > budget_s) break;
        }
        std::vector<double> sorted = times;
        std::sort(sorted.begin(), sorted.end());
        const std::size_t m = sorted.size();
        const double median = m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
        std::cout << fmt::format(
            "{{\"integrator\": \"{}\", \"rtol\": {}, \"atol\": {}, \"times_s\": [{:.5g}], \"median_s\": {:.5g}, "
            "\"error\": {}, \"steps\": {}, \"evaluations\": {}}}\n",
            name, name == "rkf45-fixed" ? std::string("null") : fmt::format("{}", rtol),
            name == "rkf45-fixed" ? std::string("null") : fmt::format("{}", rtol * 1e-6), fmt::join(times, ", "),
            median, json_number(tip_error(p, run, reference)), run.steps, run.evaluations) << std::flush;
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "transient_peers: " << e.what() << "\n";
    return 1;
  }
}
