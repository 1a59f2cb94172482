#include "chart.hpp"

#include <cstdio>
#include <stdexcept>

#include <fmt/format.h>

#include <filesystem>

#include "chart_script.hpp"
#include "options.hpp"
#include "output_files.hpp"

namespace bladestab::cli {

namespace {
// Debian's interpreter: it has python3-matplotlib, whatever python3 comes first on PATH.
constexpr const char* python = "/usr/bin/python3";

std::string shell_quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

void draw_chart(const std::string& kind, const std::string& json_path, const std::string& output_path) {
  const std::string command =
      fmt::format("{} - {} {} {}", python, kind, shell_quoted(json_path), shell_quoted(output_path));
  FILE* pipe = popen(command.c_str(), "w");
  if (pipe == nullptr) throw std::runtime_error(fmt::format("cannot start {} to draw {}", python, output_path));
  std::fputs(chart_script, pipe);
  const int status = pclose(pipe);
  if (status != 0) {
    throw std::runtime_error(fmt::format("drawing {} failed ({} with python3-matplotlib is needed)", output_path, python));
  }
}

void add_chart_options(CLI::App& command, std::string& out, std::string& chart, const std::string& out_help) {
  command.add_option("--out", out, out_help + " (default .)");
  command.add_option("--chart", chart, "chart format: png (default), svg or none")
      ->check(CLI::IsMember({"png", "svg", "none"}));
}

std::vector<std::string> write_outputs(const std::string& dir, const std::string& stem,
                                       const std::vector<std::pair<std::string, std::string>>& data,
                                       const std::string& json, const std::string& chart_kind,
                                       const std::string& chart_format) {
  const std::filesystem::path folder(dir);
  OutputFiles output;
  for (const auto& [name, text] : data) output.write((folder / name).string(), text);
  const std::string json_temporary = output.write((folder / (stem + ".json")).string(), json);
  if (chart_format != "none") {
    // Drawn from the JSON's temporary into its own: a failed drawing leaves no files at all.
    draw_chart(chart_kind, json_temporary, output.reserve((folder / (stem + "." + chart_format)).string()));
  }
  return output.commit();
}

}  // namespace bladestab::cli
