#pragma once
// An error in what the user gave us: a scene key, a command-line value. The message is one line
// that names the key, the value and what is allowed; the CLI prints it and exits non-zero.
#include <stdexcept>
#include <string>

namespace bladestab {

class InputError : public std::runtime_error {
public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace bladestab
