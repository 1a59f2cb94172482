#pragma once
// What one run may take: --max-seconds (default 600) and --max-memory (default 1024 MB). Every
// command estimates its work and memory before the heavy part starts and refuses, in one line
// naming the option that asks for it and the estimate, what would exceed them; a run that outlasts
// --max-seconds anyway (the estimates are lower bounds of the work) is stopped there
// (interruption.hpp). So an accepted value is one the program can meet.
#include <string>

#include <CLI/CLI.hpp>

#include "bladestab/blade/model.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/modal/modes.hpp"

namespace bladestab::cli {

struct WorkLimits {
  double seconds = 600;
  double megabytes = 1024;
};

// The limits of this thread's run (one command runs on a thread at a time).
WorkLimits& work_limits();

// `message` with the option that set the work limit it met: "… (--max-seconds 600)".
std::string with_max_seconds(const std::string& message);

// Adds --max-seconds and --max-memory to a command.
void add_work_limit_options(CLI::App& command);

// Throws InputError "<cause>: <what> would take about 35 min and 4.1 GB; beyond the limits of
// 600 s (--max-seconds) and 1024 MB (--max-memory)" when `seconds` or `bytes` exceeds them.
void check_work(const std::string& cause, const std::string& what, double seconds, double bytes);

// Arithmetic speeds of this code on one core, measured on the reference machine and rounded up,
// for the estimates: dense LAPACK factorizations and eigensolvers, and the small matrix–vector
// products of an integrator's right-hand side.
inline constexpr double dense_flops_per_second = 4e9;
inline constexpr double small_product_flops_per_second = 2e9;

// The memory of one whole dense eigensolve (whole_eigensolve_flops, modes.hpp): 6 (2n)² doubles.
inline double eigensolve_bytes(double dofs) { return 6 * 8 * 4 * dofs * dofs; }

// The eigensolves of modes_with_error_estimate on a model of `spec`: the model and its richer
// reference models (one for the Legendre basis, two for the sine basis). Flops; the largest
// solve's bytes.
struct EigensolveWork {
  double flops = 0, bytes = 0;
};
EigensolveWork converged_modes_work(const ModelSpec& spec, bool two_planes, bool damped);

// Bytes of a transient's history of `revolutions` at `samples_per_revolution`: each sample with its
// CSV line and chart series takes about 600.
inline double transient_history_bytes(double revolutions, int samples_per_revolution) {
  return 600 * revolutions * samples_per_revolution;
}

// Seconds of `steps` RKF45 steps of the transient's equations for a model of `dofs` dofs: six
// right-hand sides a step, each ~5 products of an n × n matrix with a vector (measured 1.0 µs at
// 24 dofs, 2.3 µs at 48).
inline double rkf45_seconds(double steps, int dofs) {
  const double n = dofs;
  return steps * 6 * 5 * (n * n + 100) / small_product_flops_per_second;
}

// Seconds of the fast transient method (exact_stepping.hpp) on `modes` modes: `magnus_steps` steps
// of the Magnus propagator on 2·modes + 1 states (magnus_step_work), and `intervals` steps of the
// state by a stored propagator.
inline double fast_transient_seconds(double magnus_steps, double intervals, int modes) {
  const double m = 2.0 * modes + 1;
  return (magnus_steps * magnus_step_work(static_cast<Eigen::Index>(m)) + intervals * 2 * m * m) /
         dense_flops_per_second;
}

}  // namespace bladestab::cli
