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

}  // namespace bladestab
