#include "json_writer.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace bladestab::cli {
namespace {

std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    switch (c) {
      case '"': q += "\\\""; break;
      case '\\': q += "\\\\"; break;
      case '\n': q += "\\n"; break;
      case '\t': q += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          q += fmt::format("\\u{:04x}", c);
        } else {
          q += c;
        }
    }
  }
  return q + "\"";
}

}  // namespace

void JsonWriter::prefix(const char* key) {
  if (!first_.empty()) {
    if (!first_.back()) out_ += ",";
    first_.back() = false;
    out_ += "\n" + std::string(2 * first_.size(), ' ');
  }
  if (key != nullptr) out_ += quoted(key) + ": ";
}

JsonWriter& JsonWriter::begin_object(const char* key) {
  prefix(key);
  out_ += "{";
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty) out_ += "\n" + std::string(2 * first_.size(), ' ');
  out_ += "}";
  if (first_.empty()) out_ += "\n";
  return *this;
}

JsonWriter& JsonWriter::begin_array(const char* key) {
  prefix(key);
  out_ += "[";
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty) out_ += "\n" + std::string(2 * first_.size(), ' ');
  out_ += "]";
  return *this;
}

JsonWriter& JsonWriter::value(const char* key, double v) {
  if (!std::isfinite(v)) throw std::logic_error(fmt::format("non-finite value for JSON key {}", key ? key : "[]"));
  prefix(key);
  out_ += fmt::format("{}", v);
  return *this;
}

JsonWriter& JsonWriter::null_value(const char* key) {
  prefix(key);
  out_ += "null";
  return *this;
}

JsonWriter& JsonWriter::value(const char* key, int v) {
  prefix(key);
  out_ += std::to_string(v);
  return *this;
}

JsonWriter& JsonWriter::value(const char* key, bool v) {
  prefix(key);
  out_ += v ? "true" : "false";
  return *this;
}

JsonWriter& JsonWriter::value(const char* key, const std::string& v) {
  prefix(key);
  out_ += quoted(v);
  return *this;
}

// Number lists go on one line: they are data columns, not structure.
JsonWriter& JsonWriter::numbers(const char* key, const std::vector<double>& values) {
  prefix(key);
  out_ += "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) throw std::logic_error(fmt::format("non-finite value in JSON list {}", key));
    out_ += fmt::format("{}{}", i ? ", " : "", values[i]);
  }
  out_ += "]";
  return *this;
}

JsonWriter& JsonWriter::numbers_or_null(const char* key, const std::vector<double>& values) {
  prefix(key);
  out_ += "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isinf(values[i])) throw std::logic_error(fmt::format("infinite value in JSON list {}", key));
    out_ += i ? ", " : "";
    out_ += std::isnan(values[i]) ? std::string("null") : fmt::format("{}", values[i]);
  }
  out_ += "]";
  return *this;
}

JsonWriter& JsonWriter::numbers(const char* key, const std::vector<int>& values) {
  prefix(key);
  out_ += "[";
  for (std::size_t i = 0; i < values.size(); ++i) out_ += fmt::format("{}{}", i ? ", " : "", values[i]);
  out_ += "]";
  return *this;
}

}  // namespace bladestab::cli
