#pragma once
// What the transient command's JSON (transient_command.cpp) and its table (transient_table.cpp)
// share: the summary of a run, its estimate as printed, and the phrases both use.
#include <optional>
#include <string>

#include "bladestab/blade/model.hpp"
#include "bladestab/scene/scene.hpp"
#include "bladestab/transient/response_analysis.hpp"
#include "bladestab/transient/transient.hpp"
#include "bladestab/transient/transient_checks.hpp"
#include "bladestab/transient/transient_error.hpp"
#include "printed_digits.hpp"

namespace bladestab::cli {

// How finely the samples resolve the faster dominant response (of the tip's lateral and axial
// deflection): its samples a period n, and how much higher than the samples' largest a sinusoid of
// that period can peak between them, 1/cos(π/n) − 1 (its crest midway between two samples). The
// peaks and their estimates are the samples'.
struct PeakSampling {
  double frequency_hz = 0, samples_per_period = 0, peak_bound = 0;
};

// The spectra, dominant frequencies, tip peaks and mean of a run, how finely its samples resolve
// the response (none without a dominant frequency), and its checks.
struct TransientSummary {
  Spectrum lateral, axial;  // empty for a history of fewer than 4 samples (a run stopped at once)
  std::optional<double> lateral_hz, axial_hz;
  double peak_lateral_m = 0, peak_axial_m = 0, mean_axial_m = 0;  // over the samples
  double sample_rate_hz = 0;
  std::optional<PeakSampling> sampling;
  TransientChecks checks;
};
std::optional<PeakSampling> peak_sampling(const TransientSummary& s);

// The run's estimate as the outputs print it, and the tolerance the run was held to (none: not
// asked; `tolerance_unmet` empty: met).
struct PrintedError {
  const std::optional<TransientErrorEstimate>& estimate;
  const std::string& unavailable;
  const PrintedDigits& digits;
  std::optional<double> tolerance = std::nullopt;
  std::string tolerance_unmet = {};
};

// Quantity `name` of the estimate (transient_error.hpp), where the run has one that is bounded.
const TransientQuantity* estimated(const std::optional<TransientErrorEstimate>& e, const std::string& name);

// What loads the tip, in one phrase.
std::string load_description(const Scene& scene);

// The table: scene, model, load, method and check lines, the tip, energy and growth lines.
// `energy_fraction`: the balance's error over the vibration energy, as computed (a check's measure).
void print_table(const Scene& scene, const BladeModel& model, const TransientOptions& o, const TransientResult& r,
                 const TransientSummary& s, double energy_fraction, const PrintedError& shown);

// The table's `error` line (each quantity's whole error and its parts) and, where a tolerance was
// asked, its `tolerance` line (which says where a peak between the samples could pass it).
void print_error(const PrintedError& error, const BladeModel& model, const std::optional<PeakSampling>& sampling);

}  // namespace bladestab::cli
