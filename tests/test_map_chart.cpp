// The map's PNG as a reader sees it: the colour under the scene's marker says unstable where the
// scene's point is unstable (the paper's scene: max|ρ| = 2.2 at θ = 300 rad/s, F̄ = 5), and stable
// (white) where it is stable. The chart script records where it drew each marker in the PNG
// ("bladestab:markers_px"); the pixels beside the marker — the "x" glyph's arms run diagonally —
// are read back with matplotlib by Debian's Python.
#include <catch2/catch.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_cli.hpp"
#include "support/scenes.hpp"

namespace fs = std::filesystem;

namespace {

std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) out += buffer.data();
  const int status = pclose(pipe);
  INFO("command: " << command << "\noutput: " << out);
  REQUIRE(status == 0);
  return out;
}

// Colours 7 pixels left, right, above and below the first marker of a PNG, as "r g b" lines in [0, 1].
constexpr const char* read_marker_colours = R"(
import struct, sys
import matplotlib.image
path = sys.argv[1]
data = open(path, "rb").read()
text, pos = {}, 8
while pos < len(data):
    size, = struct.unpack(">I", data[pos:pos + 4])
    if data[pos + 4:pos + 8] == b"tEXt":
        key, value = data[pos + 8:pos + 8 + size].split(b"\0", 1)
        text[key.decode()] = value.decode()
    pos += 12 + size
x, y = map(float, text["bladestab:markers_px"].split(";")[0].split(","))
image = matplotlib.image.imread(path)
for dx, dy in ((7, 0), (-7, 0), (0, 7), (0, -7)):
    r, g, b = image[int(round(y + dy)), int(round(x + dx))][:3]
    print(r, g, b)
)";

struct Colour {
  double r, g, b;
};

std::vector<Colour> colours_beside_marker(double fbar) {
  // In this process's private scratch directory: two suites on one machine do not share it.
  const fs::path dir = testing_support::scratch() / ("map_chart_" + std::to_string(static_cast<int>(fbar * 10)));
  fs::remove_all(dir);
  fs::create_directories(dir);
  run(std::string(BLADESTAB_EXE) + " map '" + testing_support::paper_scene_path() +
      "' --set model.terms=8 --set load.fmax_over_fcr=" + std::to_string(fbar) +
      " --plane theta-fmax --theta 200:400:5 --fmax 0:8:5 --trace 3 --resolution 20x10 --format json --out '" +
      dir.string() + "' 2>/dev/null");
  const fs::path script = dir / "read_marker.py";
  std::ofstream(script) << read_marker_colours;
  std::istringstream lines(run("/usr/bin/python3 '" + script.string() + "' '" + (dir / "map_theta_fmax.png").string() + "'"));
  std::vector<Colour> colours;
  for (Colour c{}; lines >> c.r >> c.g >> c.b;) colours.push_back(c);
  fs::remove_all(dir);
  return colours;
}

bool white(const Colour& c) { return c.r > 0.85 && c.g > 0.85 && c.b > 0.85; }  // white under the grid's lines

}  // namespace

// The marker's label or a boundary curve may cover one of the four pixels: three must agree. Two
// test cases, one map each, so that ctest runs them side by side.
TEST_CASE("the map's PNG shows the paper scene's unstable point in the unstable colour", "[map][chart][slow][parallel]") {
  const std::vector<Colour> unstable = colours_beside_marker(5.0);  // max|ρ| = 2.2: growth ×2.2 a period
  REQUIRE(unstable.size() == 4);
  CHECK(std::count_if(unstable.begin(), unstable.end(), [](const Colour& c) { return !white(c); }) >= 3);
}

TEST_CASE("the map's PNG shows the paper scene's stable point in white", "[map][chart][slow][parallel]") {
  const std::vector<Colour> stable = colours_beside_marker(0.2);  // below every tongue at θ = 300 rad/s
  REQUIRE(stable.size() == 4);
  CHECK(std::count_if(stable.begin(), stable.end(), white) >= 3);
}
