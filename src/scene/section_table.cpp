// Section tables (docs/theory.md §9): the columns, each station's values and the order of the
// stations, checked the same way whether the table is a CSV file or inline TOML.
#include "scene/section_table.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "bladestab/scene/scene_limits.hpp"
#include "support/message_text.hpp"

namespace bladestab {
namespace {

namespace limits = scene_limits;

struct Column {
  const char* name;
  bool required;
  AllowedRange allowed;
  const char* meaning;
  double SectionStation::*field;
};

const std::vector<Column>& columns() {
  static const std::vector<Column> all{
      {"span_fraction", true, AllowedRange::closed(0, 1), "s/L, 0 at the root, 1 at the tip",
       &SectionStation::span_fraction},
      {"area", true, limits::area_m2, "area in m^2", &SectionStation::area},
      {"i_flap", true, AllowedRange::above(0, 1e300), "minor principal inertia in m^4", &SectionStation::i_flap},
      {"i_edge", true, AllowedRange::above(0, 1e300), "major principal inertia in m^4, at least i_flap",
       &SectionStation::i_edge},
      {"twist_deg", true, AllowedRange::closed(-360, 360), "twist in degrees", &SectionStation::twist_deg},
      {"youngs_modulus", false, limits::youngs_modulus_pa, "Young's modulus in Pa", &SectionStation::youngs_modulus},
      {"density", false, limits::density_kg_m3, "density in kg/m^3", &SectionStation::density},
      {"shear_coefficient", false, limits::shear_coefficient, "shear coefficient κ",
       &SectionStation::shear_coefficient},
  };
  return all;
}

// One cell as the table gives it: absent, or its text and (when it reads as a finite number) value.
struct Cell {
  bool present = false;
  std::string text;
  std::optional<double> number;
};

using CellAt = std::function<Cell(const Column&)>;
using Where = std::function<std::string(const Column&)>;  // "FILE: row 3 (line 5), column area"

SectionStation station(const CellAt& cell_at, const Where& where, const SectionDefaults& defaults) {
  SectionStation s;
  s.youngs_modulus = defaults.youngs_modulus;
  s.density = defaults.density;
  s.shear_coefficient = defaults.shear_coefficient;
  for (const Column& c : columns()) {
    const Cell cell = cell_at(c);
    if (!cell.present) {
      if (c.required) throw InputError(fmt::format("{}: missing; the table needs it", where(c)));
      continue;
    }
    if (!cell.number || !std::isfinite(*cell.number) || !c.allowed.contains(*cell.number)) {
      throw InputError(fmt::format("{} = {}: must be a finite number in {} ({})", where(c), echoed(cell.text),
                                   c.allowed.text(), c.meaning));
    }
    s.*c.field = *cell.number;
  }
  if (s.i_edge < s.i_flap) {
    throw InputError(fmt::format("{} = {:g}: must be at least i_flap = {:g} (i_edge is the major principal inertia)",
                                 where(columns()[3]), s.i_edge, s.i_flap));
  }
  return s;
}

// The stations in order: at least two, span_fraction rising strictly from 0 to 1.
void check_order(const std::vector<SectionStation>& stations, const std::function<std::string(std::size_t)>& where,
                 const std::string& table) {
  if (stations.size() < 2) {
    throw InputError(fmt::format("{}: has {} station(s); a section table needs at least two (span_fraction 0 and 1)",
                                 table, stations.size()));
  }
  for (std::size_t k = 0; k < stations.size(); ++k) {
    const double x = stations[k].span_fraction;
    if (k == 0 && x != 0) {
      throw InputError(fmt::format("{} = {:g}: the first station must be at the root, span_fraction = 0", where(k), x));
    }
    if (k > 0 && !(x > stations[k - 1].span_fraction)) {
      throw InputError(fmt::format("{} = {:g}: must exceed the row before's {:g} (stations sorted root to tip, "
                                   "none repeated)", where(k), x, stations[k - 1].span_fraction));
    }
    if (k + 1 == stations.size() && x != 1) {
      throw InputError(fmt::format("{} = {:g}: the last station must be at the tip, span_fraction = 1", where(k), x));
    }
  }
}

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(trimmed(cell));
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

std::optional<double> parsed_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  return value;
}

// The header's column positions: every name known, none repeated.
std::map<std::string, std::size_t> header_columns(const std::vector<std::string>& header, const std::string& shown,
                                                  int line) {
  std::map<std::string, std::size_t> at;
  for (std::size_t k = 0; k < header.size(); ++k) {
    bool known = false;
    for (const Column& c : columns()) known = known || header[k] == c.name;
    if (!known || at.count(header[k])) {
      std::string names;
      for (const Column& c : columns()) names += (names.empty() ? "" : ", ") + std::string(c.name);
      throw InputError(fmt::format("{}: line {}, column {} '{}': {} (columns: {})", shown, line, k + 1,
                                   echoed(header[k]), known ? "repeated" : "unknown", names));
    }
    at[header[k]] = k;
  }
  return at;
}


// NREL BModes section-property files (Bir, "User's Guide to BModes", NREL/TP-500-39133): a title
// line; a line "n_secs  n_secs: number of … sections"; a blank line; the headings sec_loc str_tw
// tw_iner mass_den flp_iner edge_iner flp_stff edge_stff tor_stff axial_stff cg_offst sc_offst
// tc_offst; their units; then n_secs rows of these 13 numbers, separated by blanks or tabs.
const std::vector<std::string> bmodes_headings{"sec_loc",  "str_tw",   "tw_iner",   "mass_den", "flp_iner",
                                               "edge_iner", "flp_stff", "edge_stff", "tor_stff", "axial_stff",
                                               "cg_offst", "sc_offst", "tc_offst"};

std::vector<std::string> split_blanks(const std::string& line) {
  std::vector<std::string> words;
  std::stringstream in(line);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

// Whether `lines` (the file's) are a BModes section file: its second line names n_secs.
bool is_bmodes_file(const std::vector<std::string>& lines) {
  if (lines.size() < 2) return false;
  const std::vector<std::string> words = split_blanks(lines[1]);
  return words.size() >= 2 && words[1].rfind("n_secs", 0) == 0;
}

// A BModes table as stations: sec_loc the span fraction, str_tw the twist; with [blade]'s density
// ρ, A = mass_den/ρ, E = axial_stff/A, I_flap = flp_stff/E, I_edge = edge_stff/E, so that ρA, EA and
// both EI are the file's. The model has no offsets and one twist: cg, sc and tc offsets must be 0
// and tw_iner = str_tw; flp_iner, edge_iner and tor_stff are not used (the rotary inertia is ρI).
std::vector<SectionStation> read_bmodes(const std::vector<std::string>& lines, const std::string& shown,
                                        const SectionDefaults& defaults) {
  const std::optional<double> count = parsed_number(split_blanks(lines[1])[0]);
  if (!count || *count < 2 || *count != std::floor(*count) || *count + 5 > static_cast<double>(lines.size())) {
    throw InputError(fmt::format("{}: line 2, n_secs = {}: must be a whole number of sections, at least 2, with "
                                 "that many rows after the headings and units (lines 4 and 5)",
                                 shown, echoed(split_blanks(lines[1])[0])));
  }
  if (split_blanks(lines[3]) != bmodes_headings) {
    throw InputError(fmt::format("{}: line 4: must be the BModes headings {}", shown, fmt::join(bmodes_headings, " ")));
  }
  std::vector<SectionStation> stations;
  for (int row = 1; row <= static_cast<int>(*count); ++row) {
    const int number = row + 5;
    const std::vector<std::string> words = split_blanks(lines[number - 1]);
    const auto where_in_file = [&](const std::string& heading) {
      return fmt::format("{}: row {} (line {}), column {}", shown, row, number, heading);
    };
    if (words.size() != bmodes_headings.size()) {
      throw InputError(fmt::format("{}: row {} (line {}): has {} values for the {} BModes columns", shown, row, number,
                                   words.size(), bmodes_headings.size()));
    }
    std::vector<double> v;
    for (std::size_t k = 0; k < words.size(); ++k) {
      const std::optional<double> x = parsed_number(words[k]);
      if (!x || !std::isfinite(*x)) {
        throw InputError(fmt::format("{} = {}: must be a finite number", where_in_file(bmodes_headings[k]),
                                     echoed(words[k])));
      }
      v.push_back(*x);
    }
    for (std::size_t k : {10, 11, 12}) {
      if (v[k] != 0) {
        throw InputError(fmt::format("{} = {}: must be 0 (the model's mass centre, shear centre and tension centre "
                                     "lie on the elastic axis)", where_in_file(bmodes_headings[k]), words[k]));
      }
    }
    if (v[2] != v[1]) {
      throw InputError(fmt::format("{} = {}: must equal str_tw = {} (the model has one twist)",
                                   where_in_file("tw_iner"), words[2], words[1]));
    }
    const double area = v[3] / defaults.density, modulus = v[9] / area;
    const std::map<std::string, std::pair<std::string, double>> cells{
        {"span_fraction", {"sec_loc", v[0]}},          {"twist_deg", {"str_tw", v[1]}},
        {"area", {"mass_den / blade.density", area}},  {"youngs_modulus", {"axial_stff / area", modulus}},
        {"i_flap", {"flp_stff / E", v[6] / modulus}}, {"i_edge", {"edge_stff / E", v[7] / modulus}}};
    const CellAt cell_at = [&](const Column& c) {
      const auto it = cells.find(c.name);
      if (it == cells.end()) return Cell{};
      return Cell{true, fmt::format("{:g}", it->second.second), it->second.second};
    };
    const Where where = [&](const Column& c) {
      const auto it = cells.find(c.name);
      return where_in_file(it == cells.end() ? c.name : it->second.first);
    };
    stations.push_back(station(cell_at, where, defaults));
  }
  check_order(stations, [&](std::size_t k) {
    return fmt::format("{}: row {} (line {}), column sec_loc", shown, k + 1, k + 6);
  }, shown);
  return stations;
}

}  // namespace

const std::vector<std::string>& section_columns() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Column& c : columns()) out.push_back(c.name);
    return out;
  }();
  return names;
}

std::vector<SectionStation> read_section_file(const std::string& path, const std::string& shown,
                                              const SectionDefaults& defaults) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot read the section table (blade.sections)", shown));
  std::vector<std::string> file;
  for (std::string line; std::getline(in, line);) file.push_back(line);
  if (is_bmodes_file(file)) return read_bmodes(file, shown, defaults);
  std::vector<SectionStation> stations;
  std::vector<int> lines;
  std::map<std::string, std::size_t> at;
  bool have_header = false;
  for (int number = 1; number <= static_cast<int>(file.size()); ++number) {
    const std::string text = trimmed(file[number - 1]);
    if (text.empty() || text[0] == '#') continue;
    const std::vector<std::string> cells = split_csv(text);
    if (!have_header) {
      at = header_columns(cells, shown, number);
      have_header = true;
      continue;
    }
    const std::size_t row = stations.size() + 1;
    if (cells.size() != at.size()) {
      throw InputError(fmt::format("{}: row {} (line {}): has {} values for {} columns", shown, row, number,
                                   cells.size(), at.size()));
    }
    const CellAt cell_at = [&](const Column& c) {
      const auto it = at.find(c.name);
      if (it == at.end()) return Cell{};
      return Cell{true, cells[it->second], parsed_number(cells[it->second])};
    };
    const Where where = [&](const Column& c) {
      return at.count(c.name) ? fmt::format("{}: row {} (line {}), column {}", shown, row, number, c.name)
                              : fmt::format("{}: column {}", shown, c.name);
    };
    stations.push_back(station(cell_at, where, defaults));
    lines.push_back(number);
  }
  check_order(stations, [&](std::size_t k) {
    return fmt::format("{}: row {} (line {}), column span_fraction", shown, k + 1, lines[k]);
  }, shown);
  return stations;
}

std::vector<SectionStation> read_section_tables(const toml::array& tables, const std::string& source,
                                                const SectionDefaults& defaults) {
  std::vector<SectionStation> stations;
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const toml::table* table = tables.get(k)->as_table();
    const std::string row = fmt::format("{}: blade.section[{}]", source, k + 1);
    if (table == nullptr) throw InputError(row + ": must be a table ([[blade.section]])");
    for (const auto& [key, node] : *table) {
      bool known = false;
      for (const Column& c : columns()) known = known || key.str() == c.name;
      if (!known) {
        throw SceneKeyError(fmt::format("{}.{}: unknown key (known: {})", row, echoed(key.str()),
                                        fmt::join(section_columns(), ", ")),
                            "blade.section", SceneKeyError::Reason::unknown);
      }
    }
    const CellAt cell_at = [&](const Column& c) {
      const toml::node* node = table->get(c.name);
      if (node == nullptr) return Cell{};
      std::optional<double> number;
      if (node->is_floating_point()) number = node->as_floating_point()->get();
      if (node->is_integer()) number = static_cast<double>(node->as_integer()->get());
      std::ostringstream text;
      node->visit([&text](auto&& v) { text << v; });
      return Cell{true, text.str(), number};
    };
    const Where where = [&](const Column& c) { return fmt::format("{}.{}", row, c.name); };
    stations.push_back(station(cell_at, where, defaults));
  }
  check_order(stations, [&](std::size_t k) { return fmt::format("{}: blade.section[{}].span_fraction", source, k + 1); },
              source + ": [[blade.section]]");
  return stations;
}

std::vector<SectionStation> read_blade_sections(const toml::table& blade, const std::string& scene_path,
                                                const std::string& source, const SectionDefaults& defaults) {
  if (blade.contains("sections") && blade.contains("section")) {
    throw InputError(fmt::format("{}: blade.sections and [[blade.section]]: give the section table once, as a CSV "
                                 "file or as tables", source));
  }
  if (const toml::node* tables = blade.get("section")) {
    if (!tables->is_array()) {
      throw SceneKeyError(fmt::format("{}: blade.section: must be [[blade.section]] tables", source), "blade.section",
                          SceneKeyError::Reason::not_numeric);
    }
    return read_section_tables(*tables->as_array(), source, defaults);
  }
  const toml::node* file = blade.get("sections");
  if (file == nullptr) return {};
  if (!file->is_string() || file->as_string()->get().empty()) {
    throw SceneKeyError(fmt::format("{}: blade.sections: must be a non-empty file name in quotes", source),
                        "blade.sections", SceneKeyError::Reason::not_numeric);
  }
  const std::string name = file->as_string()->get();
  const std::string::size_type slash = scene_path.find_last_of('/');
  const std::string path =
      name[0] == '/' || slash == std::string::npos ? name : scene_path.substr(0, slash + 1) + name;
  return read_section_file(path, echoed(path, 240), defaults);
}

}  // namespace bladestab
