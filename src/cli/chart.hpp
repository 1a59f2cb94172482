#pragma once
// Charts are drawn by scripts/charts/ (compiled into the program) with Debian's matplotlib.
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace bladestab::cli {

// Renders `kind` from the JSON file `json_path` into `temporary` (.png or .svg) with the chart
// script in a child process (interruption.hpp ends it if the run is stopped). Throws InputError
// when the chart cannot be written (as for every output file: output_files.hpp), else
// std::runtime_error when drawing fails; either names `output_path` (the file the temporary
// becomes) and the script's reason in one line.
void draw_chart(const std::string& kind, const std::string& json_path, const std::string& temporary,
                const std::string& output_path);

// --out DIR and --chart png|svg|none, shared by the commands that draw.
void add_chart_options(CLI::App& command, std::string& out, std::string& chart, const std::string& out_help);

// Writes each {file name, text} of `data` and `<stem>.json` into `dir`, then draws the chart
// `<stem>.<format>` from the JSON unless the format is "none". Returns the paths written (and hands
// them to an embedded run's answer, embedding.hpp).
std::vector<std::string> write_outputs(const std::string& dir, const std::string& stem,
                                       const std::vector<std::pair<std::string, std::string>>& data,
                                       const std::string& json, const std::string& chart_kind,
                                       const std::string& chart_format);

}  // namespace bladestab::cli
