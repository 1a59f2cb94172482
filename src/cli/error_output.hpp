#pragma once
// How an ErrorBudget appears in the outputs: JSON keys `error_estimate` (the total) and
// `error_budget` {basis, reduction, load, method, unbounded}, and one table line.
#include <string>

#include "bladestab/base/error_budget.hpp"
#include "json_output.hpp"
#include "printed_digits.hpp"

namespace bladestab::cli {

// Sets `error_estimate` and `error_budget` in the JSON object `json`, each to 2 digits (rounded up).
void write_error_budget(Json& json, const ErrorBudget& budget, const PrintedDigits& digits);

// "3.1e-07 (basis 2.0e-07, reduction 1.0e-07, load 0, method 1.0e-08)", plus "; not bounded: …".
std::string describe_error_budget(const ErrorBudget& budget);

}  // namespace bladestab::cli
