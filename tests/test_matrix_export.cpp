// `stability --export-matrices`: the program writes the periodic system its Floquet analysis
// integrated (Matrix Market + a JSON manifest, for the benchmark's SciPy integrators in bench/).
// Read back, the arrays must be the ones periodic_system() builds for the same fidelity.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "bladestab/stability/matrix_export.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "support/json.hpp"
#include "support/scenes.hpp"

namespace {

namespace fs = std::filesystem;
using namespace bladestab;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.cols() == b.cols());
  return (a - b).norm() / b.norm();
}

// Runs the program with the export and checks what it wrote against periodic_system().
void check_export(const std::vector<std::string>& overrides, const std::string& tolerance, int expected_states) {
  const fs::path dir = fs::temp_directory_path() / ("bladestab_export_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path manifest = dir / "system.json";
  std::string command = std::string(BLADESTAB_EXE) + " stability '" + testing_support::paper_scene_path() +
                        "' --tolerance " + tolerance + " --export-matrices '" + manifest.string() + "'";
  for (const std::string& o : overrides) command += " --set " + o;
  command += " > '" + (dir / "stdout").string() + "'";
  INFO(command);
  REQUIRE(std::system(command.c_str()) == 0);

  INFO(read_text(manifest));
  const testing_support::Json json = testing_support::parse_json(read_text(manifest));
  const Scene scene = testing_support::paper_scene(overrides);
  ModelSpec spec = scene.model;
  spec.terms = static_cast<int>(json["terms"].number);
  ReductionSpec reduction = scene.model.reduction;
  reduction.vectors = static_cast<int>(json["reduction_vectors"].number);
  CHECK(json["reduction"].text == to_string(reduction.kind));
  const PeriodicSystem expected = periodic_system(assemble_model(scene, spec), scene, load_series(scene), reduction);
  if (expected_states > 0) CHECK(expected.state_size() == expected_states);
  CHECK(json["states"].number == expected.state_size());
  CHECK(json["theta_rad_s"].number == Approx(expected.angular_frequency).epsilon(1e-15));
  CHECK(json["period_s"].number == Approx(expected.period()).epsilon(1e-15));
  CHECK(json["A0"].text == "system.A0.mtx");

  // The same arrays up to rounding: the program and this test may differ in vectorization and BLAS
  // threads. They do under the sanitizers: A0 1.7e-14, and B 5e-12 for the whole 48-state model,
  // whose modal coordinates carry the eigenvectors' rounding, ε ω²_max / gap. A lost sign
  // convention gives O(1), a wrong load level 1e-3.
  const PeriodicSystem read = read_matrix_market((dir / "system").string());
  CHECK(relative_difference(read.A0, expected.A0) <= 1e-12);
  CHECK(relative_difference(read.B, expected.B) <= 1e-10);
  REQUIRE(read.coefficients.size() == expected.coefficients.size());
  for (std::size_t m = 0; m < read.coefficients.size(); ++m) {
    CHECK(std::abs(read.coefficients[m] - expected.coefficients[m]) <= 1e-15 * std::abs(expected.coefficients[m]));
  }
  // The program's own answer and its estimate are in the manifest (the value is 2.1992296566;
  // the 8-term model is 2e-6 below it, which its basis part reports).
  CHECK(json["max_abs_multiplier"].number == Approx(2.19923).epsilon(1e-5));
  CHECK(json["error_estimate"].number > 0);
  fs::remove_all(dir);
}

}  // namespace

TEST_CASE("stability --export-matrices writes the system it integrated (export)", "[export][parallel][long_under_sanitizers]") {
  SECTION("the whole 8-term Ritz model") {
    check_export({"model.terms=8", "model.reduction=none"}, "1e-5", 48);
  }
  SECTION("the scene as it ships, reduced") {
    check_export({}, "1e-6", -1);
  }
}

TEST_CASE("Matrix Market files round-trip every double (export)", "[export]") {
  PeriodicSystem sys;
  sys.A0 = Eigen::MatrixXd::Random(7, 7) * 1e5;
  sys.A0(2, 3) = 1.0 / 3.0;
  sys.A0(4, 1) = 4.9e-320;  // subnormal
  sys.B = Eigen::MatrixXd::Zero(7, 7);
  sys.B.bottomLeftCorner(3, 4) = Eigen::MatrixXd::Random(3, 4) * 1e-7;
  sys.coefficients = {{-1.5, 0}, {0.25, -1e-17}, {std::nextafter(1.0, 2.0), 3.0}};
  const fs::path stem = fs::temp_directory_path() / ("bladestab_roundtrip_" + std::to_string(::getpid()));
  write_matrix_market(sys, stem.string());
  const PeriodicSystem read = read_matrix_market(stem.string());
  CHECK(read.A0 == sys.A0);
  CHECK(read.B == sys.B);
  CHECK(read.coefficients == sys.coefficients);
  for (const std::string& f : {matrix_market_files(stem.string()).A0, matrix_market_files(stem.string()).B,
                               matrix_market_files(stem.string()).load}) {
    fs::remove(f);
  }
}
