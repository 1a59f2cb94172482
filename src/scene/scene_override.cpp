#include "scene/scene_override.hpp"

#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "support/message_text.hpp"

namespace bladestab {

void apply_override(toml::table& root, const std::string& assignment) {
  const std::string shown = echoed(assignment);
  const auto eq = assignment.find('=');
  const auto dot = assignment.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot > eq || dot == 0 || dot + 1 == eq) {
    throw ParameterError("set", fmt::format("{}: must have the form section.key=value", shown));
  }
  const std::string section = assignment.substr(0, dot);
  const std::string key = assignment.substr(dot + 1, eq - dot - 1);
  const std::string text = assignment.substr(eq + 1);
  if (text.empty()) {
    throw ParameterError("set", fmt::format("{}: the value is empty", shown));
  }
  // One value on one line: a line break would let the text go on with keys of its own.
  if (text.find_first_of("\r\n") != std::string::npos) {
    throw ParameterError("set", fmt::format("{}: the value spans lines; give one value on one line", shown));
  }
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + text);
  } catch (const toml::parse_error&) {
    parsed.insert_or_assign("value", text);  // a bare word: take it as a string
  }
  toml::node* node = root.get(section);
  if (node == nullptr) {
    root.insert_or_assign(section, toml::table{});
    node = root.get(section);
  }
  toml::table* table = node->as_table();
  if (table == nullptr) throw ParameterError("set", fmt::format("{}: {} is not a table", shown, echoed(section)));
  table->insert_or_assign(key, *parsed.get("value"));
}

}  // namespace bladestab
