#pragma once
// Numbers on the command line, read the same way by every option of every command: plain decimal
// (no hex, no spaces, not empty), finite, and within the option's allowed range, checked while the
// command line is parsed. A value that fails is echoed as typed — an empty one as '', not as the 0
// a number conversion would make of it — in one InputError line naming the option.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bladestab/scene/allowed_range.hpp"

namespace bladestab::cli {

// The upper limit of an integer option that has none of its own.
inline constexpr long max_int = std::numeric_limits<int>::max();

// "12", "-0.5", "1e-3", ".5": the number; anything else ("0x10", " 3", "nan", "1e999", ""): nullopt.
std::optional<double> read_decimal(const std::string& text);
// "12", "-3": the number; anything else, and values beyond a long: nullopt.
std::optional<long> read_integer(const std::string& text);

// "must be a number in (0, 1)", "must be an integer >= 1": what an option accepts, for messages.
std::string number_rule(const AllowedRange& allowed);
std::string integer_rule(long lo, long hi);

CLI::Option* add_number_option(CLI::App& command, const std::string& name, double& target,
                               const AllowedRange& allowed, const std::string& help);
CLI::Option* add_integer_option(CLI::App& command, const std::string& name, int& target, long lo, long hi,
                                const std::string& help);
// Comma-separated lists ("1,2,5"); the option may also be repeated. A list names a set: not
// empty, each value once, each allowed — the rule of a scene's list (allowed_range.hpp).
CLI::Option* add_number_list_option(CLI::App& command, const std::string& name, std::vector<double>& target,
                                    const AllowedRange& allowed, const std::string& help);
CLI::Option* add_integer_list_option(CLI::App& command, const std::string& name, std::vector<int>& target, long lo,
                                     long hi, const std::string& help);

}  // namespace bladestab::cli
