#include "work_limits.hpp"

#include <fmt/format.h>

#include "bladestab/scene/allowed_range.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "number_options.hpp"

namespace bladestab::cli {
namespace {

std::string duration_text(double seconds) {
  if (seconds < 120) return fmt::format("{:.3g} s", seconds);
  if (seconds < 7200) return fmt::format("{:.3g} min", seconds / 60);
  if (seconds < 2 * 86400) return fmt::format("{:.3g} h", seconds / 3600);
  return fmt::format("{:.3g} days", seconds / 86400);
}

std::string size_text(double bytes) {
  if (bytes < 1e6) return fmt::format("{:.3g} kB", bytes / 1e3);
  if (bytes < 1e9) return fmt::format("{:.3g} MB", bytes / 1e6);
  return fmt::format("{:.3g} GB", bytes / 1e9);
}

}  // namespace

WorkLimits& work_limits() {
  thread_local WorkLimits limits;
  return limits;
}

void add_work_limit_options(CLI::App& command) {
  WorkLimits& limits = work_limits();
  // Below 0.1 s the program's own start (a few ms, more on a loaded machine) could outlast the
  // limit before a refusal is printed: such a limit is refused as a value instead.
  add_number_option(command, "--max-seconds", limits.seconds, AllowedRange::closed(0.1, 1e7),
                    "refuse work estimated to take longer, and stop a run that does (default 600, at least 0.1)");
  add_number_option(command, "--max-memory", limits.megabytes, AllowedRange::above(0, 1e7),
                    "refuse work estimated to need more memory, in MB (default 1024)");
}

void check_work(const std::string& cause, const std::string& what, double seconds, double bytes) {
  const WorkLimits& limits = work_limits();
  if (seconds <= limits.seconds && bytes <= limits.megabytes * 1e6) return;
  throw InputError(fmt::format("{}: {} would take about {} and {}; beyond the limits of {:g} s (--max-seconds) and "
                               "{:g} MB (--max-memory)",
                               cause, what, duration_text(seconds), size_text(bytes), limits.seconds,
                               limits.megabytes));
}

std::string with_max_seconds(const std::string& message) {
  return fmt::format("{} (--max-seconds {:g})", message, work_limits().seconds);
}

EigensolveWork converged_modes_work(const ModelSpec& spec, bool two_planes, bool damped) {
  const ReferenceSolves solves = reference_solves(spec, two_planes, damped);
  return {solves.flops, eigensolve_bytes(solves.largest_dofs)};
}

}  // namespace bladestab::cli
