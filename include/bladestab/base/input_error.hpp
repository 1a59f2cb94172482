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

// An InputError about a parameter of an analysis, a field of its options ("tolerance", "harmonics",
// "method", a sweep's "key", "values" and "count", a scene's override "set"), not a scene key. The
// message starts with the parameter's name and value, "tolerance 1e-13: …"; a program that gives
// the parameter another name (bladestab's options are "--" and the name) rewrites that start.
class ParameterError : public InputError {
public:
  ParameterError(std::string parameter, const std::string& rest)
      : InputError(parameter + " " + rest), parameter_(std::move(parameter)) {}
  const std::string& parameter() const { return parameter_; }

private:
  std::string parameter_;
};

// An InputError about one scene key ("section.key"; a section alone for an unknown section), with
// how it failed, so that a caller that set the key itself (a parameter sweep) can tell a key the scene
// does not have or does not use, or one that takes no number, from a value the key does not allow.
class SceneKeyError : public InputError {
public:
  enum class Reason {
    unknown,      // no such key (or section)
    unused,       // a known key that the other settings leave without meaning
    not_numeric,  // the key takes a string, a boolean or a list
    not_allowed,  // the value is of the right kind but not allowed
  };
  SceneKeyError(const std::string& message, std::string key, Reason reason)
      : InputError(message), key_(std::move(key)), reason_(reason) {}
  const std::string& key() const { return key_; }
  Reason reason() const { return reason_; }

private:
  std::string key_;
  Reason reason_;
};

}  // namespace bladestab
