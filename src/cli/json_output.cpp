#include "json_output.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace bladestab::cli {
namespace {

// One token: a scalar, or an object's key. Bytes that are not UTF-8 (a scene path can hold any)
// become U+FFFD instead of failing the whole document. A double is written in fmt's shortest form
// that reads back as it, as the CSV files write it: nlohmann's own is not always the shortest
// (measured: 16 of 20 000 rounded values, 75.00712300000001 for 75.007123), and the digits printed
// are chosen (printed_digits.hpp).
std::string token(const Json& scalar, const std::string& key) {
  if (!scalar.is_number_float()) return scalar.dump(-1, ' ', false, Json::error_handler_t::replace);
  const double value = scalar.get<double>();
  if (!std::isfinite(value)) {
    throw std::logic_error(fmt::format("non-finite value for JSON key {}", key.empty() ? "[]" : key));
  }
  return fmt::format("{}", value);
}

bool number_list(const Json& value) {
  return value.is_array() && std::all_of(value.begin(), value.end(), [](const Json& v) {
           return v.is_number() || v.is_null();
         });
}

void lay_out(const Json& value, const std::string& key, int depth, std::string& out) {
  if (!value.is_structured()) {
    out += token(value, key);
    return;
  }
  const bool object = value.is_object();
  if (value.empty()) {
    out += object ? "{}" : "[]";
    return;
  }
  if (number_list(value)) {
    out += "[";
    for (auto it = value.begin(); it != value.end(); ++it) out += (it == value.begin() ? "" : ", ") + token(*it, key);
    out += "]";
    return;
  }
  const std::string indent(2 * (depth + 1), ' ');
  out += object ? "{" : "[";
  for (auto it = value.begin(); it != value.end(); ++it) {
    out += (it == value.begin() ? "\n" : ",\n") + indent;
    if (object) out += token(Json(it.key()), it.key()) + ": ";
    lay_out(it.value(), object ? it.key() : key, depth + 1, out);
  }
  out += "\n" + std::string(2 * depth, ' ') + (object ? "}" : "]");
}

}  // namespace

std::string json_text(const Json& document) {
  std::string out;
  lay_out(document, "", 0, out);
  return out + "\n";
}

Json number_or_null(double value) { return std::isnan(value) ? Json(nullptr) : Json(value); }

Json numbers_or_null(const std::vector<double>& values) {
  Json list = Json::array();
  for (const double v : values) list.push_back(number_or_null(v));
  return list;
}

}  // namespace bladestab::cli
