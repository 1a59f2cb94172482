#pragma once
// The program's --format json output as the tests read it: parsed by nlohmann::json (which throws
// nlohmann::json::parse_error on malformed input) into a plain tree of values.
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace testing_support {

struct Json {
  enum class Type { null, boolean, number, string, array, object };
  Type type = Type::null;
  bool boolean = false;
  double number = 0;
  std::string text;
  std::vector<Json> items;            // array
  std::map<std::string, Json> members;  // object

  bool has(const std::string& key) const { return type == Type::object && members.count(key) != 0; }
  const Json& operator[](const std::string& key) const {
    const auto it = members.find(key);
    if (type != Type::object || it == members.end()) throw std::runtime_error("JSON: no key \"" + key + "\"");
    return it->second;
  }
  const Json& operator[](std::size_t index) const { return items.at(index); }
  std::size_t size() const { return type == Type::array ? items.size() : members.size(); }
  std::vector<double> numbers() const {
    std::vector<double> out;
    for (const Json& item : items) out.push_back(item.number);
    return out;
  }
};

inline Json from_parsed(const nlohmann::json& value) {
  Json v;
  if (value.is_object()) {
    v.type = Json::Type::object;
    for (const auto& [key, member] : value.items()) v.members[key] = from_parsed(member);
  } else if (value.is_array()) {
    v.type = Json::Type::array;
    for (const nlohmann::json& item : value) v.items.push_back(from_parsed(item));
  } else if (value.is_string()) {
    v.type = Json::Type::string;
    v.text = value.get<std::string>();
  } else if (value.is_boolean()) {
    v.type = Json::Type::boolean;
    v.boolean = value.get<bool>();
  } else if (value.is_number()) {
    v.type = Json::Type::number;
    v.number = value.get<double>();
  }
  return v;
}

inline Json parse_json(const std::string& text) { return from_parsed(nlohmann::json::parse(text)); }

// Half the unit of the last digit of a value printed with absolute error `error` by default: the
// unit is the largest power of ten ≤ the error (docs/outputs.md), so the printing moves the value
// by at most this.
inline double half_printed_unit(double error) { return 0.5 * std::pow(10.0, std::floor(std::log10(error))); }

}  // namespace testing_support
