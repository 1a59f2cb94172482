#pragma once
// A blade's section table (docs/theory.md §9): read from a CSV file (blade.sections) or from inline
// [[blade.section]] tables, each station checked. Bad tables get one InputError line naming the
// file (or key), the row and the column.
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "bladestab/scene/scene.hpp"

namespace bladestab {

// What a station takes from [blade] when its table has no column for it.
struct SectionDefaults {
  double youngs_modulus = 0, density = 0, shear_coefficient = 0;
};

// The CSV file at `path` (`shown`: its name in messages): a header row naming the columns
// span_fraction, area, i_flap, i_edge, twist_deg and optionally youngs_modulus, density,
// shear_coefficient, in any order; then one row per station. Blank lines and lines starting with
// '#' are skipped. Or, recognised by its second line naming n_secs, an NREL BModes section file
// (its mass, axial and bending stiffnesses and twist per station; [blade]'s density gives the area).
std::vector<SectionStation> read_section_file(const std::string& path, const std::string& shown,
                                              const SectionDefaults& defaults);

// The same table as TOML tables, one per station (`source`: the scene's name in messages).
std::vector<SectionStation> read_section_tables(const toml::array& tables, const std::string& source,
                                                const SectionDefaults& defaults);

// The section table of a [blade] table: blade.sections (a CSV file, its path relative to the
// directory of `scene_path`) or [[blade.section]]; empty without either (`source`: the scene's
// name in messages).
std::vector<SectionStation> read_blade_sections(const toml::table& blade, const std::string& scene_path,
                                                const std::string& source, const SectionDefaults& defaults);

// The columns, as the messages list them.
const std::vector<std::string>& section_columns();

}  // namespace bladestab
