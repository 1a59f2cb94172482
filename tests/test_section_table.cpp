// Section tables (docs/theory.md §9, docs/guide.md): a CSV file beside the scene or inline
// [[blade.section]] tables, and the one-line refusal of a bad table naming file, row and column.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include "bladestab/base/input_error.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/scene/scene.hpp"
#include "support/run_cli.hpp"
#include "support/scene_text.hpp"

using namespace bladestab;
using testing_support::expect_rejected;
using testing_support::scratch;

namespace {

const std::string blade_keys = R"(length = 0.6
hub_radius = 0.35
youngs_modulus = 117e9
density = 4466.0
poisson = 0.3
shear_coefficient = 0.833
stagger_deg = -30.0
)";

const std::string other_sections = "\n" + testing_support::legendre_model_section + R"([operation]
speed_rad_s = 300.0
[damping]
model = "none"
[load]
profile = "half-sine"
fmax_over_fcr = 1.0
contact_time_rev = 0.01
pulses_per_rev = 1
pulse_count = 0
approximation = "cosine"
mode = "force"
friction = 0.0
clearance = 0.003
)";

const std::string good_csv = "span_fraction,area,i_flap,i_edge,twist_deg,density\n"
                             "0,4e-3,2e-7,1e-5,0,4466\n"
                             "0.5,3e-3,1e-7,9e-6,20,4400\n"
                             "1,2e-3,1e-8,7e-6,50,4300\n";

// A scene in the scratch directory naming `csv_name` (written beside it with `csv`); its path.
std::string scene_with_table(const std::string& csv_name, const std::string& csv) {
  const auto dir = scratch() / "tables";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / csv_name) << csv;
  const auto path = dir / ("scene_" + csv_name + ".toml");
  std::ofstream(path) << "[blade]\n" << blade_keys << "sections = \"" << csv_name << "\"\n" << other_sections;
  return path.string();
}

std::string refusal(const std::string& csv) {
  static int count = 0;
  const std::string path = scene_with_table("bad" + std::to_string(++count) + ".csv", csv);
  try {
    load_scene(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("A section table from a CSV file beside the scene", "[section-table]") {
  const Scene scene = load_scene(scene_with_table("good.csv", good_csv));
  REQUIRE(scene.blade.sections.size() == 3);
  CHECK(scene.blade.sections[1].span_fraction == 0.5);
  CHECK(scene.blade.sections[1].i_edge == 9e-6);
  CHECK(scene.blade.sections[2].twist_deg == 50);
  CHECK(scene.blade.sections[2].density == 4300);
  CHECK(scene.blade.sections[2].youngs_modulus == 117e9);  // no column: [blade]'s
  CHECK(scene.blade.area == 4e-3);                          // the root station's
  CHECK(scene.blade.twist_scale == 1);
}

TEST_CASE("The same table inline as [[blade.section]] gives the same scene", "[section-table]") {
  std::string text = "[blade]\n" + blade_keys + "twist_scale = 0.5\n";
  const char* rows[3] = {"span_fraction = 0\narea = 4e-3\ni_flap = 2e-7\ni_edge = 1e-5\ntwist_deg = 0\ndensity = 4466\n",
                         "span_fraction = 0.5\narea = 3e-3\ni_flap = 1e-7\ni_edge = 9e-6\ntwist_deg = 20\ndensity = 4400\n",
                         "span_fraction = 1\narea = 2e-3\ni_flap = 1e-8\ni_edge = 7e-6\ntwist_deg = 50\ndensity = 4300\n"};
  for (const char* row : rows) text += std::string("[[blade.section]]\n") + row;
  const Scene inline_scene = parse_scene(text + other_sections, "inline.toml");
  const Scene file_scene = load_scene(scene_with_table("same.csv", good_csv));
  REQUIRE(inline_scene.blade.sections.size() == 3);
  for (int k = 0; k < 3; ++k) {
    CHECK(inline_scene.blade.sections[k].i_flap == file_scene.blade.sections[k].i_flap);
    CHECK(inline_scene.blade.sections[k].twist_deg == file_scene.blade.sections[k].twist_deg);
  }
  CHECK(inline_scene.blade.twist_scale == 0.5);
  CHECK_THROWS_WITH(parse_scene("[blade]\n" + blade_keys + "twist_scale = 2\narea = 1e-3\nslenderness = 0.01\n" +
                                    other_sections, "uniform.toml"),
                    Catch::Contains("blade.twist_scale = 2") && Catch::Contains("not used with a uniform blade"));
}

TEST_CASE("Bad section tables: one line naming the file, the row and the column", "[section-table]") {
  const std::string header = "span_fraction,area,i_flap,i_edge,twist_deg\n";
  CHECK_THAT(refusal("span_fraction,area,i_flap,twist_deg\n0,1e-3,1e-7,0\n1,1e-3,1e-7,0\n"),
             Catch::Contains("bad1.csv") && Catch::Contains("column i_edge: missing"));
  CHECK_THAT(refusal(header + "0,1e-3,1e-7,1e-6,0\n0.6,1e-3,1e-7,1e-6,0\n0.4,1e-3,1e-7,1e-6,0\n1,1e-3,1e-7,1e-6,0\n"),
             Catch::Contains("row 3 (line 4), column span_fraction = 0.4") && Catch::Contains("must exceed"));
  CHECK_THAT(refusal(header + "0,1e-3,1e-7,1e-6,0\n0.5,1e-3,1e-7,1e-6,0\n0.5,1e-3,1e-7,1e-6,0\n1,1e-3,1e-7,1e-6,0\n"),
             Catch::Contains("row 3 (line 4), column span_fraction = 0.5"));
  CHECK_THAT(refusal(header + "0.1,1e-3,1e-7,1e-6,0\n1,1e-3,1e-7,1e-6,0\n"),
             Catch::Contains("row 1 (line 2), column span_fraction = 0.1") && Catch::Contains("at the root"));
  CHECK_THAT(refusal(header + "0,1e-3,1e-7,1e-6,0\n0.9,1e-3,1e-7,1e-6,0\n"),
             Catch::Contains("row 2 (line 3), column span_fraction = 0.9") && Catch::Contains("at the tip"));
  CHECK_THAT(refusal(header + "0,1e-3,1e-7,1e-6,0\n1,-1e-3,1e-7,1e-6,0\n"),
             Catch::Contains("row 2 (line 3), column area = -1e-3"));
  CHECK_THAT(refusal(header + "0,1e-3,1e-7,1e-6,0\n1,1e-3,0,1e-6,0\n"), Catch::Contains("row 2 (line 3), column i_flap = 0"));
  CHECK_THAT(refusal(header + "0,1e-3,1e-7,1e-8,0\n1,1e-3,1e-7,1e-6,0\n"),
             Catch::Contains("row 1 (line 2), column i_edge = 1e-08") && Catch::Contains("at least i_flap"));
  CHECK_THAT(refusal(header + "0,1e-3,1e-7,1e-6,0\n"), Catch::Contains("at least two"));
  CHECK_THAT(refusal(header + "0,1e-3,1e-7,1e-6,zero\n1,1e-3,1e-7,1e-6,0\n"),
             Catch::Contains("row 1 (line 2), column twist_deg = zero"));
  CHECK_THAT(refusal("span_fraction,area,i_flap,i_edge,twist_deg,chord\n"), Catch::Contains("column 6 'chord': unknown"));
}

TEST_CASE("The program refuses a bad section table with exit 2 and one line", "[section-table]") {
  const std::string path =
      scene_with_table("cli.csv", "span_fraction,area,i_flap,i_edge,twist_deg\n0,1e-3,1e-7,1e-6,0\n1,1e-3,2e-6,1e-6,0\n");
  expect_rejected({"modes", path}, {"cli.csv: row 2 (line 3), column i_edge = 1e-06", "at least i_flap"});
}

namespace {

// An NREL BModes section file (BModes user's guide, NREL/TP-500-39133) of a uniform, untwisted
// titanium section, A = 2e-3 m², I_flap = 1e-7 m⁴, I_edge = 1e-5 m⁴, E = 117 GPa, ρ = 4466 kg/m³:
// ρA = 8.932 kg/m, EA = 2.34e8 N, EI = 11700 and 1.17e6 N m²; `row2` replaces its second row.
std::string bmodes_file(const std::string& row2 = "0.5\t0.0\t0.0\t8.932\t0.1\t0.1\t11700\t1.17e6\t5000\t2.34e8\t0.0\t0.0\t0.0") {
  return "Uniform titanium test section\n"
         "  3     n_secs:     number of blade or tower sections at which properties are specified (-)\n"
         "\n"
         "sec_loc  str_tw  tw_iner  mass_den  flp_iner  edge_iner  flp_stff  edge_stff  tor_stff  axial_stff  cg_offst  sc_offst  tc_offst\n"
         "  (-)    (deg)    (deg)    (kg/m)    (kg-m)    (kg-m)     (Nm^2)     (Nm^2)     (Nm^2)      (N)        (m)       (m)      (m)\n"
         "0.0     0.0     0.0     8.932     0.1      0.1      11700     1.17e6     5000      2.34e8      0.0       0.0       0.0\n" +
         row2 + "\n" +
         "1.0     0.0     0.0     8.932     0.1      0.1      11700     1.17e6     5000      2.34e8      0.0       0.0       0.0\n";
}

}  // namespace

TEST_CASE("An NREL BModes section file is read by its format", "[section-table][bmodes]") {
  const Scene scene = load_scene(scene_with_table("blade.dat", bmodes_file()));
  REQUIRE(scene.blade.sections.size() == 3);
  for (const SectionStation& s : scene.blade.sections) {
    CHECK(s.area == Approx(2e-3).epsilon(1e-14));
    CHECK(s.youngs_modulus == Approx(117e9).epsilon(1e-14));
    CHECK(s.i_flap == Approx(1e-7).epsilon(1e-14));
    CHECK(s.i_edge == Approx(1e-5).epsilon(1e-14));
    CHECK(s.density == 4466);
    CHECK(s.twist_deg == 0);
  }
  CHECK(scene.blade.sections[1].span_fraction == 0.5);
  // The uniform untwisted blade buckles at π²EI_flap/(4L²), EI_flap the file's flp_stff.
  const double pi = 3.14159265358979323846, L = scene.blade.length;
  CHECK(assemble_model(scene).blade.critical_load() == Approx(pi * pi * 11700 / (4 * L * L)).epsilon(1e-10));
}

TEST_CASE("Bad BModes section files: one line naming the file, the row and the BModes column", "[section-table][bmodes]") {
  const auto refused = [](const std::string& name, const std::string& text) -> std::string {
    try {
      load_scene(scene_with_table(name, text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  CHECK_THAT(refused("offset.dat", bmodes_file("0.5 0 0 8.932 0.1 0.1 11700 1.17e6 5000 2.34e8 0.01 0 0")),
             Catch::Contains("offset.dat: row 2 (line 7), column cg_offst = 0.01") && Catch::Contains("must be 0"));
  CHECK_THAT(refused("twist.dat", bmodes_file("0.5 10 12 8.932 0.1 0.1 11700 1.17e6 5000 2.34e8 0 0 0")),
             Catch::Contains("row 2 (line 7), column tw_iner = 12") && Catch::Contains("str_tw = 10"));
  CHECK_THAT(refused("edge.dat", bmodes_file("0.5 0 0 8.932 0.1 0.1 11700 1000 5000 2.34e8 0 0 0")),
             Catch::Contains("row 2 (line 7), column edge_stff / E") && Catch::Contains("at least i_flap"));
  CHECK_THAT(refused("short.dat", bmodes_file("0.5 0 0 8.932")),
             Catch::Contains("row 2 (line 7): has 4 values for the 13 BModes columns"));
  CHECK_THAT(refused("order.dat", bmodes_file("1.5 0 0 8.932 0.1 0.1 11700 1.17e6 5000 2.34e8 0 0 0")),
             Catch::Contains("row 2 (line 7), column sec_loc = 1.5"));
}
