#include "chart.hpp"

#include <cstdio>
#include <stdexcept>

#include <fmt/format.h>

#include "chart_script.hpp"

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

}  // namespace bladestab::cli
