#pragma once
// A `--set section.key=value` override applied to a scene's TOML before it is read: the value
// parsed as TOML (a bare word as a string), one value on one line.
#include <string>

#include <toml++/toml.h>

namespace bladestab {

// Sets root[section][key] (a new section where there is none); ParameterError("set", …) naming the
// assignment where it is not section.key=value, its value is empty or spans lines, or the section
// is no table.
void apply_override(toml::table& root, const std::string& assignment);

}  // namespace bladestab
