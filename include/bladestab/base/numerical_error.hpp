#pragma once
// A computation that failed its own checks (a residual, an invariant, a second method) and could
// not be repaired by raising the fidelity. The message is one line saying which check failed, by
// how much, and what to change; the CLI prints it and exits with status 1. Never a number.
#include <stdexcept>
#include <string>

namespace bladestab {

class NumericalError : public std::runtime_error {
public:
  explicit NumericalError(const std::string& message) : std::runtime_error(message) {}
};

// A refinement stopped where its next level would take more work than the caller allows (its
// flops: FloquetOptions::max_flops, StabilityRequest::work_flops); the CLI names --max-seconds.
class WorkLimitError : public NumericalError {
public:
  explicit WorkLimitError(const std::string& message) : NumericalError(message) {}
};

// Whether a caught failure is a work limit's (WorkLimitError), which its reporter names.
inline bool is_work_limit(const std::exception& e) { return dynamic_cast<const WorkLimitError*>(&e) != nullptr; }

}  // namespace bladestab
