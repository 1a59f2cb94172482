#include "number_options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <regex>

#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "support/message_text.hpp"

namespace bladestab::cli {
namespace {

// What a list option was given: every value of every occurrence, split at commas.
std::vector<std::string> list_items(const std::vector<std::string>& values) {
  std::vector<std::string> items;
  for (const std::string& value : values) {
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = value.find(',', start);
      items.push_back(value.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  return items;
}

std::string joined(const std::vector<std::string>& values) {
  std::string text;
  for (const std::string& v : values) text += (text.empty() ? "" : ",") + v;
  return text;
}

// "--points 1,,2: an empty item; must be …", "--points 1,-2: -2 is not allowed; must be …".
[[noreturn]] void refuse_item(const std::string& name, const std::vector<std::string>& values, const std::string& item,
                              const std::string& rule) {
  const std::string what = item.empty() ? "an empty item" : fmt::format("{} is not allowed", echoed(item));
  throw InputError(fmt::format("{} {}: {}; {}", name, echoed(joined(values)), what, rule));
}

// A list names a set: each value once, as a scene's list (allowed_range.hpp).
void refuse_repeat(const std::string& name, const std::vector<std::string>& values, const std::vector<double>& numbers,
                   const std::string& rule) {
  if (const std::optional<double> repeated = first_repeat(numbers)) {
    throw InputError(fmt::format("{} {}: {:g} is given twice; {}", name, echoed(joined(values)), *repeated, rule));
  }
}

}  // namespace

std::optional<double> read_decimal(const std::string& text) {
  // strtod alone would also take hex, "inf", "nan" and leading spaces.
  static const std::regex decimal(R"([+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?)");
  if (!std::regex_match(text, decimal)) return std::nullopt;
  const double value = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long> read_integer(const std::string& text) {
  static const std::regex integer(R"([+-]?[0-9]+)");
  if (!std::regex_match(text, integer)) return std::nullopt;
  errno = 0;
  const long value = std::strtol(text.c_str(), nullptr, 10);
  if (errno == ERANGE) return std::nullopt;
  return value;
}

std::string number_rule(const AllowedRange& allowed) { return "must be a number in " + allowed.text(); }

std::string integer_rule(long lo, long hi) {
  if (hi == max_int) return fmt::format("must be an integer >= {}", lo);
  return fmt::format("must be an integer in [{}, {}]", lo, hi);
}

CLI::Option* add_number_option(CLI::App& command, const std::string& name, double& target,
                               const AllowedRange& allowed, const std::string& help) {
  return command.add_option_function<std::string>(
      name,
      [name, &target, allowed](const std::string& text) {
        const std::optional<double> value = read_decimal(text);
        if (!value || !allowed.contains(*value)) {
          throw InputError(fmt::format("{} {}: {}", name, echoed(text), number_rule(allowed)));
        }
        target = *value;
      },
      help)->type_name("NUMBER");
}

CLI::Option* add_integer_option(CLI::App& command, const std::string& name, int& target, long lo, long hi,
                                const std::string& help) {
  return command.add_option_function<std::string>(
      name,
      [name, &target, lo, hi](const std::string& text) {
        const std::optional<long> value = read_integer(text);
        if (!value || *value < lo || *value > hi) {
          throw InputError(fmt::format("{} {}: {}", name, echoed(text), integer_rule(lo, hi)));
        }
        target = static_cast<int>(*value);
      },
      help)->type_name("INTEGER");
}

CLI::Option* add_number_list_option(CLI::App& command, const std::string& name, std::vector<double>& target,
                                    const AllowedRange& allowed, const std::string& help) {
  return command.add_option_function<std::vector<std::string>>(
      name,
      [name, &target, allowed](const std::vector<std::string>& values) {
        const std::string rule = distinct_numbers_rule(allowed);
        std::vector<double> numbers;
        for (const std::string& item : list_items(values)) {
          const std::optional<double> value = read_decimal(item);
          if (!value || !allowed.contains(*value)) refuse_item(name, values, item, rule);
          numbers.push_back(*value);
        }
        refuse_repeat(name, values, numbers, rule);
        target = numbers;
      },
      help)->type_name("LIST")->allow_extra_args(false);  // one word each: `--points 1 SCENE` keeps its scene
}

CLI::Option* add_integer_list_option(CLI::App& command, const std::string& name, std::vector<int>& target, long lo,
                                     long hi, const std::string& help) {
  return command.add_option_function<std::vector<std::string>>(
      name,
      [name, &target, lo, hi](const std::vector<std::string>& values) {
        const std::string rule = distinct_integers_rule(lo, hi);
        std::vector<double> numbers;
        for (const std::string& item : list_items(values)) {
          const std::optional<long> value = read_integer(item);
          if (!value || *value < lo || *value > hi) refuse_item(name, values, item, rule);
          numbers.push_back(static_cast<double>(*value));
        }
        refuse_repeat(name, values, numbers, rule);
        target = std::vector<int>(numbers.begin(), numbers.end());
      },
      help)->type_name("LIST")->allow_extra_args(false);
}

}  // namespace bladestab::cli
