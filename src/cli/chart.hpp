#pragma once
// Charts are drawn by scripts/charts.py (compiled into the program) with Debian's matplotlib.
#include <string>

namespace bladestab::cli {

// Writes `json` next to `output` (same stem, .json) and renders `kind` to `output` (.png or .svg).
// Throws std::runtime_error with the interpreter's message when drawing fails.
void draw_chart(const std::string& kind, const std::string& json_path, const std::string& output_path);

}  // namespace bladestab::cli
