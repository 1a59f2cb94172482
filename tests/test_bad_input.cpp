// Bad input end to end: run the real `bladestab` program on broken scenes and command lines and check
// that it refuses them the way the input-error contract says (tests/support/run_cli.hpp): exit 2,
// nothing on stdout, one line on stderr naming the key or option, the value and what is allowed.
//
// The ctest names carry "(bad_input)" so that `ctest -R bad_input` selects them.
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "support/json.hpp"
#include "support/run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using testing_support::describe;
using testing_support::expect_rejected;
using testing_support::read_text;
using testing_support::scratch;

const std::string valid_scene = BLADESTAB_SOURCE_DIR "/stability_maps/sinha2005/blade.toml";

// `bladestab modes <valid scene> extra...`
std::vector<std::string> modes(std::vector<std::string> extra = {}) {
  extra.insert(extra.begin(), {"modes", valid_scene});
  return extra;
}

// `bladestab campbell <valid scene> --speeds <speeds> extra...`, writing nothing outside the scratch dir.
std::vector<std::string> campbell(const std::string& speeds, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"campbell", valid_scene, "--speeds", speeds, "--out", scratch().string(),
                                "--chart", "none"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// A copy of the valid scene in the scratch dir with the line `key = ...` replaced by `replacement`
// (which may be empty or several lines), and `appended` added at the end.
std::string edited_scene(const std::string& file_name, const std::string& key, const std::string& replacement,
                         const std::string& appended = "") {
  std::istringstream in(read_text(valid_scene));
  std::string text;
  bool replaced = key.empty();
  for (std::string line; std::getline(in, line);) {
    const bool match = !replaced && line.rfind(key, 0) == 0 &&
                       line.find_first_not_of(' ', key.size()) == line.find('=', key.size());
    if (match) {
      if (!replacement.empty()) text += replacement + "\n";
      replaced = true;
    } else {
      text += line + "\n";
    }
  }
  REQUIRE(replaced);
  text += appended;
  const fs::path path = scratch() / file_name;
  std::ofstream(path) << text;
  return path.string();
}

struct SetCase {
  std::string assignment;             // --set section.key=value on the valid scene
  std::vector<std::string> expected;  // see expect_rejected
};

void run_set_cases(const std::vector<SetCase>& cases) {
  for (const SetCase& c : cases) {
    DYNAMIC_SECTION("modes --set " << c.assignment) { expect_rejected(modes({"--set", c.assignment}), c.expected); }
  }
}

}  // namespace

TEST_CASE("bad input: out-of-range and non-finite scene numbers (bad_input)", "[bad_input]") {
  run_set_cases({
      {"blade.youngs_modulus=-1", {"blade.youngs_modulus = -1", "[1e5, 1e13]"}},
      {"blade.youngs_modulus=0", {"blade.youngs_modulus = 0", "[1e5, 1e13]"}},
      {"blade.youngs_modulus=nan", {"blade.youngs_modulus = nan", "finite"}},
      {"blade.density=inf", {"blade.density = inf", "finite"}},
      {"blade.poisson=0.5", {"blade.poisson = 0.5", "(-1, 0.5)"}},
      {"blade.poisson=0.6", {"blade.poisson = 0.6", "(-1, 0.5)"}},
      {"blade.poisson=-1", {"blade.poisson = -1", "(-1, 0.5)"}},
      {"blade.shear_coefficient=1.5", {"blade.shear_coefficient = 1.5", "[0.05, 1]"}},
      {"blade.shear_coefficient=0", {"blade.shear_coefficient = 0", "[0.05, 1]"}},
      {"blade.stagger_deg=91", {"blade.stagger_deg = 91", "[-90, 90]"}},
      {"model.terms=0", {"model.terms = 0", "[1, 200]"}},
      {"operation.speed_rad_s=-5", {"operation.speed_rad_s = -5", "[0, 1e5]"}},
      {"load.contact_time_rev=0", {"load.contact_time_rev = 0", "[1e-6, 1]"}},
      {"load.friction=-0.1", {"load.friction = -0.1", "[0, 2]"}},
  });
}

TEST_CASE("bad input: wrong types and unknown choices in the scene (bad_input)", "[bad_input]") {
  run_set_cases({
      {"model.terms=2.5", {"model.terms = 2.5", "integer"}},
      {"model.terms=ten", {"model.terms = \"ten\"", "integer"}},
      {"model.basis=chebyshev", {"model.basis = \"chebyshev\"", "\"legendre\"", "\"sine\""}},
      {"model.theory=timoshenk", {"model.theory = \"timoshenk\"", "\"timoshenko\"", "\"euler-bernoulli\""}},
      {"model.axial=yes", {"model.axial = \"yes\"", "true or false"}},
      {"damping.model=viscous", {"damping.model = \"viscous\"", "\"modal\"", "\"rayleigh\""}},
      {"load.profile=square", {"load.profile = \"square\"", "\"half-sine\"", "\"rectangular\""}},
      {"blade.colour=red", {"blade.colour = \"red\"", "unknown key", "youngs_modulus"}},
      // The keys a section may omit are named too.
      {"load.bogus=1", {"load.bogus = 1", "unknown key", "pulse_frequency_hz"}},
  });
}

TEST_CASE("bad input: inconsistent scene settings (bad_input)", "[bad_input]") {
  SECTION("paper damping at speed 0") {
    expect_rejected(modes({"--set", "damping.model=paper", "--set", "damping.ratio=0.01", "--set",
                           "operation.speed_rad_s=0"}),
                    {"damping.model = \"paper\"", "operation.speed_rad_s > 0"});
  }
  SECTION("modal damping without a ratio") {
    expect_rejected(modes({"--set", "damping.model=modal"}), {"damping.ratio", "missing", "required"});
  }
  SECTION("rayleigh damping with equal frequencies") {
    expect_rejected(modes({"--set", "damping.model=rayleigh", "--set", "damping.ratio=0.01", "--set",
                           "damping.frequencies_hz=[100, 100]"}),
                    {"damping.frequencies_hz = [100, 100]", "must differ"});
  }
  SECTION("overlapping pulses") {
    expect_rejected(modes({"--set", "load.pulses_per_rev=2", "--set", "load.contact_time_rev=0.6"}),
                    {"load.contact_time_rev = 0.6", "1/pulses_per_rev"});
  }
}

TEST_CASE("bad input: broken scene files (bad_input)", "[bad_input]") {
  struct FileCase {
    std::string file;                        // name of the edited copy
    std::string key, replacement, appended;  // see edited_scene
    std::vector<std::string> expected;       // "{scene}" stands for the edited copy's path
  };
  const std::vector<FileCase> cases = {
      {"no_length.toml", "length", "", "", {"blade.length", "missing", "required"}},
      {"neither.toml", "slenderness", "", "", {"blade.slenderness", "blade.inertia", "missing", "exactly one"}},
      {"both.toml", "slenderness", "slenderness = 0.01\ninertia = 2.239e-7", "",
       {"blade.slenderness", "blade.inertia", "exactly one", "0.01|2.239e-07|2.239e-7"}},
      {"unknown_key.toml", "speed_rad_s", "speed_rad_s = 300.0\nrpm = 2865", "",
       {"operation.rpm = 2865", "unknown key", "speed_rad_s"}},
      {"unknown_section.toml", "", "", "\n[rotor]\nblades = 24\n", {"[rotor]", "unknown section", "known: blade"}},
      {"invalid.toml", "length", "length = 1.0.0", "", {"{scene}:9:", "not valid TOML"}},
      {"terms_string.toml", "terms", "terms = \"ten\"", "", {"model.terms = \"ten\"", "integer"}},
      {"terms_float.toml", "terms", "terms = 2.5", "", {"model.terms = 2.5", "integer"}},
      {"modulus_nan.toml", "youngs_modulus", "youngs_modulus = nan", "", {"blade.youngs_modulus = nan", "finite"}},
      {"density_inf.toml", "density", "density = inf", "", {"blade.density = inf", "finite"}},
  };
  for (const FileCase& c : cases) {
    DYNAMIC_SECTION("modes " << c.file) {
      const std::string path = edited_scene(c.file, c.key, c.replacement, c.appended);
      std::vector<std::string> expected = c.expected;
      for (std::string& e : expected) {
        if (const auto at = e.find("{scene}"); at != std::string::npos) e.replace(at, 7, path);
      }
      expect_rejected({"modes", path}, expected);
    }
  }
}

TEST_CASE("bad input: missing scene file and malformed --set (bad_input)", "[bad_input]") {
  SECTION("nonexistent scene file") {
    const std::string missing = (scratch() / "no_such_scene.toml").string();
    expect_rejected({"modes", missing}, {missing, "cannot read"});
  }
  SECTION("empty scene file") {
    const std::string empty = (scratch() / "empty.toml").string();
    std::ofstream{empty};
    expect_rejected({"modes", empty}, {empty, "[blade]", "missing section"});
  }
  SECTION("--set without '='") {
    expect_rejected(modes({"--set", "blade.length"}), {"--set blade.length", "section.key=value"});
  }
  SECTION("--set without '.'") {
    expect_rejected(modes({"--set", "bladelength=1"}), {"--set bladelength=1", "section.key=value"});
  }
  SECTION("--set with an empty value") {
    expect_rejected(modes({"--set", "blade.length="}), {"--set blade.length=", "empty"});
  }
  SECTION("--set with a value that goes on past a line break (its keys were taken silently)") {
    expect_rejected(modes({"--set", "model.terms=4\nx=1"}), {"--set model.terms=4", "spans lines", "one line"});
  }
}

TEST_CASE("bad input: campbell options (bad_input)", "[bad_input][parallel]") {
  SECTION("reversed speed range") {
    expect_rejected(campbell("600:0:10"), {"--speeds 600:0:10", "start < stop"});
  }
  SECTION("a single speed") { expect_rejected(campbell("0:600:1"), {"--speeds 0:600:1", "count in [2, "}); }
  SECTION("speeds not a range") { expect_rejected(campbell("abc"), {"--speeds abc", "start:stop:count"}); }
  SECTION("negative speeds") { expect_rejected(campbell("-10:600:10"), {"--speeds -10:600:10", "[0, 1e5]"}); }
  SECTION("engine order 0") {
    expect_rejected(campbell("0:600:10", {"--engine-orders", "0"}), {"--engine-orders", " 0 ", "[1, 1000]"});
  }
  SECTION("no modes to track") {
    expect_rejected(campbell("0:600:10", {"--count", "0"}), {"--count 0", ">= 1"});
  }
  SECTION("--tolerance 0") {
    expect_rejected(campbell("0:600:10", {"--tolerance", "0"}), {"--tolerance 0", "(0, 1)"});
  }
  SECTION("--tolerance nan") {
    expect_rejected(campbell("0:600:10", {"--tolerance", "nan"}), {"--tolerance nan", "(0, 1)"});
  }
  SECTION("--tolerance below the rounding") {
    expect_rejected(campbell("0:600:10", {"--tolerance", "1e-13"}), {"--tolerance 1e-13", "1e-12"});
  }
  SECTION("--tolerance the sine basis cannot reach") {
    expect_rejected(campbell("0:600:10", {"--set", "model.basis=sine", "--tolerance", "1e-6"}),
                    {"--tolerance 1e-06", "not met", "legendre"});
  }
}

TEST_CASE("bad input: modes options and command-line parse errors (bad_input)", "[bad_input]") {
  SECTION("--count 0") { expect_rejected(modes({"--count", "0"}), {"--count 0", ">= 1"}); }
  SECTION("--tolerance 2") { expect_rejected(modes({"--tolerance", "2"}), {"--tolerance 2", "(0, 1)"}); }
  SECTION("--tolerance nan") { expect_rejected(modes({"--tolerance", "nan"}), {"--tolerance nan", "(0, 1)"}); }
  SECTION("--tolerance below the rounding") {
    expect_rejected(modes({"--tolerance", "1e-13"}), {"--tolerance 1e-13", "1e-12"});
  }
  SECTION("--count not a number") { expect_rejected(modes({"--count", "abc"}), {"--count", "abc", "integer"}); }
  SECTION("--format unknown") { expect_rejected(modes({"--format", "xml"}), {"--format", "xml", "json"}); }
  SECTION("unknown option") { expect_rejected(modes({"--bogus"}), {"--bogus", "--help"}); }
  SECTION("unknown subcommand") {
    expect_rejected({"frobnicate", valid_scene}, {"frobnicate", "modes", "campbell"});
  }
}

TEST_CASE("bad input: stability, boundaries and map options (bad_input)", "[bad_input]") {
  const auto with = [](std::vector<std::string> args) {
    args.insert(args.begin() + 1, valid_scene);
    return args;
  };
  SECTION("stability --method unknown") {
    expect_rejected(with({"stability", "--method", "floquet"}), {"--method", "floquet", "koopman-hill"});
  }
  SECTION("stability --tolerance 0") {
    expect_rejected(with({"stability", "--tolerance", "0"}), {"--tolerance 0", "(0, 1)"});
  }
  SECTION("stability --harmonics 100") {
    expect_rejected(with({"stability", "--harmonics", "100"}), {"--harmonics 100", "[1, 60]"});
  }
  SECTION("stability at rest without a pulse frequency") {
    expect_rejected(with({"stability", "--set", "operation.speed_rad_s=0"}),
                    {"operation.speed_rad_s = 0", "load.pulse_frequency_hz"});
  }
  SECTION("stability with a Fourier series of an impulse") {
    expect_rejected(with({"stability", "--set", "load.profile=impulse", "--set", "load.approximation=fourier"}),
                    {"load.profile = \"impulse\"", "Fourier series"});
  }
  SECTION("stability --export-matrices to a file that is not a .json manifest") {
    expect_rejected(with({"stability", "--export-matrices", (scratch() / "system.npz").string()}),
                    {"--export-matrices", "system.npz", "FILE.json"});
  }
  SECTION("stability --export-matrices below a regular file") {
    std::ofstream(scratch() / "plain_file") << "x";
    expect_rejected(with({"stability", "--export-matrices", (scratch() / "plain_file" / "system.json").string()}),
                    {"--export-matrices", "plain_file/system.json", "cannot write"});
  }
  SECTION("stability --export-matrices of the true pulse train") {
    expect_rejected(with({"stability", "--set", "load.approximation=exact", "--export-matrices",
                          (scratch() / "exact.json").string()}),
                    {"--export-matrices", "load.approximation = \"exact\"", "no series"});
    CHECK(!fs::exists(scratch() / "exact.json"));
  }
  SECTION("boundaries of the true pulse train") {
    // Its edges would be the mean load's tongue tips, both at one speed (284.32294 rad/s, where
    // `stability` finds the tongue from 283.7 to 284.95).
    expect_rejected(with({"boundaries", "--set", "load.approximation=exact"}),
                    {"load.approximation = \"exact\"", "need the load as a series", "\"fourier\""});
  }
  SECTION("boundaries --approximation 0") {
    expect_rejected(with({"boundaries", "--approximation", "0"}), {"--approximation 0", "[1, 36]"});
  }
  SECTION("boundaries --tolerance 2") {
    expect_rejected(with({"boundaries", "--tolerance", "2"}), {"--tolerance 2", "(0, 1)"});
  }
  SECTION("boundaries --range 5") {
    expect_rejected(with({"boundaries", "--range", "5"}), {"--range 5", "LO:HI"});
  }
  SECTION("boundaries --range 9:3") {
    expect_rejected(with({"boundaries", "--range", "9:3"}), {"--range 9:3", "0 <= LO < HI"});
  }
  SECTION("boundaries --at-theta -5") {
    expect_rejected(with({"boundaries", "--at-theta", "-5"}), {"--at-theta -5", "(0, 1e9]"});
  }
  SECTION("map without a plane") { expect_rejected(with({"map"}), {"--plane", "required"}); }
  SECTION("map speed plane without speeds") {
    expect_rejected(with({"map", "--plane", "speed-fmax", "--chart", "none"}), {"--speeds", "required"});
  }
  SECTION("map with the other plane's grid") {
    expect_rejected(with({"map", "--plane", "theta-fmax", "--speeds", "100:600:4", "--chart", "none"}),
                    {"--speeds 100:600:4", "only with --plane speed-fmax"});
    expect_rejected(with({"map", "--plane", "speed-fmax", "--speeds", "100:600:4", "--theta", "100:600:4", "--chart", "none"}),
                    {"--theta 100:600:4", "only with --plane theta-fmax"});
  }
  SECTION("map empty F range") {
    expect_rejected(with({"map", "--plane", "theta-fmax", "--fmax", "5:5:3", "--chart", "none"}),
                    {"--fmax 5:5:3", "start < stop"});
  }
  SECTION("map negative pulse frequency") {
    expect_rejected(with({"map", "--plane", "theta-fmax", "--theta", "-100:100:3", "--chart", "none"}),
                    {"--theta -100:100:3", "(0, 1e9]"});
  }
  SECTION("map --threads 0") {
    expect_rejected(with({"map", "--plane", "theta-fmax", "--threads", "0", "--chart", "none"}),
                    {"--threads 0", "[1, 256]"});
  }
  SECTION("map --max-order 0") {
    expect_rejected(with({"map", "--plane", "theta-fmax", "--max-order", "0", "--chart", "none"}),
                    {"--max-order 0", "[1, 40]"});
  }
}

TEST_CASE("bad input: transient and crosscheck options (bad_input)", "[bad_input]") {
  const auto with = [](std::vector<std::string> args) {
    args.insert(args.begin() + 1, valid_scene);
    return args;
  };
  SECTION("transient --revolutions 0") {
    expect_rejected(with({"transient", "--revolutions", "0", "--chart", "none"}), {"--revolutions 0", "(0, 1e5]"});
  }
  SECTION("transient --step unknown") {
    expect_rejected(with({"transient", "--step", "implicit"}), {"--step", "implicit", "adaptive"});
  }
  SECTION("transient --samples-per-rev 2") {
    expect_rejected(with({"transient", "--samples-per-rev", "2", "--chart", "none"}), {"--samples-per-rev 2", "[8, 100000]"});
  }
  SECTION("transient --steps-per-period below the paper's 8") {
    expect_rejected(with({"transient", "--step", "fixed", "--steps-per-period", "4", "--chart", "none"}),
                    {"--steps-per-period 4", "[8, 100000]"});
  }
  SECTION("transient --steps-per-period without --step fixed") {
    expect_rejected(with({"transient", "--steps-per-period", "16", "--chart", "none"}), {"--steps-per-period 16", "--step fixed"});
  }
  SECTION("transient --name with a slash") {
    expect_rejected(with({"transient", "--name", "a/b", "--revolutions", "0.1", "--chart", "none"}), {"--name a/b", "no '/'"});
  }
  SECTION("clearance mode without the casing's intrusion") {
    expect_rejected(with({"transient", "--set", "load.mode=clearance", "--revolutions", "0.1", "--chart", "none"}),
                    {"load.intrusion", "missing", "required"});
  }
  SECTION("clearance mode with a negative intrusion") {
    expect_rejected(with({"transient", "--set", "load.mode=clearance", "--set", "load.intrusion=-1e-3", "--chart", "none"}),
                    {"load.intrusion = -0.001", "[0, 10]"});
  }
  SECTION("clearance mode with an impulse for the casing's shape") {
    expect_rejected(with({"transient", "--set", "load.mode=clearance", "--set", "load.intrusion=1e-3", "--set",
                          "load.profile=impulse", "--chart", "none"}),
                    {"load.profile = \"impulse\"", "clearance", "half-sine"});
  }
  SECTION("an intrusion in force mode") {
    expect_rejected(with({"transient", "--set", "load.intrusion=1e-3", "--chart", "none"}),
                    {"load.intrusion = 0.001", "not used with load.mode = \"force\""});
  }
  SECTION("a zero contact stiffness") {
    expect_rejected(with({"transient", "--set", "load.mode=clearance", "--set", "load.intrusion=1e-3", "--set",
                          "load.contact_stiffness=0", "--chart", "none"}),
                    {"load.contact_stiffness = 0", "[0.001, 1e15]"});
  }
  SECTION("crosscheck --points negative") {
    expect_rejected(with({"crosscheck", "--points", "1,-2"}), {"--points", "-2", "[0, 1000]"});
  }
  SECTION("crosscheck --revolutions 1") {
    expect_rejected(with({"crosscheck", "--revolutions", "1"}), {"--revolutions 1", "[6, 1000]"});
  }
}

// Issue 11's hostile runs, one or more per class it found; each used to crash, hang, print NaN with
// exit 0, write a multi-line or misdirected error, or leave files behind.
TEST_CASE("bad input: issue 11, crashes on non-finite numerics (bad_input)", "[bad_input]") {
  const std::string out = (scratch() / "issue11").string();
  SECTION("boundaries --at-theta inf") { expect_rejected({"boundaries", valid_scene, "--at-theta", "inf"}, {"--at-theta inf", "(0, 1e9]"}); }
  SECTION("boundaries --at-theta 1e308") { expect_rejected({"boundaries", valid_scene, "--at-theta", "1e308"}, {"--at-theta 1e308", "(0, 1e9]"}); }
  SECTION("boundaries --at-theta beyond the contact") {
    expect_rejected({"boundaries", valid_scene, "--at-theta", "1e6"}, {"--at-theta 1e+06", "load.contact_time_rev", "Ω/t̄_c"});
  }
  SECTION("map --fmax 0:1e308:3") {
    expect_rejected({"map", valid_scene, "--plane", "theta-fmax", "--fmax", "0:1e308:3", "--out", out, "--chart", "none"},
                    {"--fmax 0:1e308:3", "[0, 1000]"});
  }
  SECTION("boundaries with blade.youngs_modulus=1e308") {
    expect_rejected({"boundaries", valid_scene, "--set", "blade.youngs_modulus=1e308"},
                    {"blade.youngs_modulus = 1e+308", "[1e5, 1e13]"});
  }
  SECTION("map with load.fmax_over_fcr=1e308") {
    expect_rejected({"map", valid_scene, "--plane", "theta-fmax", "--set", "load.fmax_over_fcr=1e308", "--out", out, "--chart", "none"},
                    {"load.fmax_over_fcr = 1e+308", "[0, 1000]"});
  }
  SECTION("Koopman-Hill with Rayleigh damping at 1e-300 Hz") {
    expect_rejected({"stability", valid_scene, "--method", "koopman-hill", "--set", "damping.model=rayleigh", "--set",
                     "damping.ratio=0.01", "--set", "damping.frequencies_hz=[1e-300,2e-300]"},
                    {"damping.frequencies_hz = [1e-300, 2e-300]", "[0.001, 1e9]"});
  }
  SECTION("the Magnus exponential of a Fourier load with a contact of 1e-308 rev") {
    expect_rejected({"stability", valid_scene, "--set", "load.approximation=fourier", "--set", "load.contact_time_rev=1e-308"},
                    {"load.contact_time_rev = 1e-308", "[1e-6, 1]"});
  }
  SECTION("campbell with blade.youngs_modulus=1e-308") {
    expect_rejected({"campbell", valid_scene, "--speeds", "0:600:3", "--set", "blade.youngs_modulus=1e-308", "--out", out,
                     "--chart", "none"},
                    {"blade.youngs_modulus = 1e-308"});
  }
  SECTION("modes with blade.youngs_modulus=1e-308 (printed Λ = nan with exit 0; then blamed speed_rad_s)") {
    const auto o = expect_rejected(modes({"--set", "blade.youngs_modulus=1e-308"}), {"blade.youngs_modulus = 1e-308", "[1e5, 1e13]"});
    CHECK(o.err.find("speed_rad_s") == std::string::npos);
  }
}

TEST_CASE("bad input: issue 11, work and memory beyond the limits (bad_input)", "[bad_input][parallel]") {
  const std::string out = (scratch() / "issue11").string();
  const std::vector<std::string> estimate{"would take about", "--max-seconds", "--max-memory"};
  const auto with = [&](std::vector<std::string> args, const std::vector<std::string>& more) {
    std::vector<std::string> expected = estimate;
    expected.insert(expected.end(), more.begin(), more.end());
    return std::pair{args, expected};
  };
  for (const auto& [args, expected] : {
           with({"transient", valid_scene, "--revolutions", "100000", "--out", out, "--chart", "none"}, {"--revolutions 100000"}),
           with({"transient", valid_scene, "--set", "model.terms=200", "--out", out, "--chart", "none"}, {"model.terms = 200"}),
           with({"map", valid_scene, "--plane", "theta-fmax", "--trace", "100000", "--out", out, "--chart", "none"}, {"--trace 100000"}),
           with({"boundaries", valid_scene, "--set", "model.reduction=none", "--approximation", "36"}, {"--approximation 36"}),
           // The automatic reduction's comparison with the whole model (seed 2034: 90 s and 1.6 GB).
           with({"boundaries", valid_scene, "--set", "model.terms=178"}, {"model.terms = 178", "whole model of 534 dofs"}),
           // The shipped scene's cross-check at 40 terms: about 17 s, estimated 80 s.
           with({"crosscheck", valid_scene, "--set", "model.terms=40", "--max-seconds", "5"}, {"--points", "model.terms = 40"}),
       }) {
    DYNAMIC_SECTION(args[0] << " " << args.back()) { expect_rejected(args, expected); }
  }
  SECTION("stability --method hill --harmonics 60") {
    expect_rejected({"stability", valid_scene, "--method", "hill", "--harmonics", "60"}, {"--harmonics 60", "rows", "1200"});
  }
  SECTION("a run that outlasts --max-seconds is stopped there, with one line and no output") {
    // 0.5 s of CPU at --tolerance 1e-9, whose estimate is far below the limit.
    const auto o = testing_support::run_bladestab({"stability", valid_scene, "--tolerance", "1e-9", "--max-seconds", "0.1"});
    INFO(o.command << "\n" << describe(o) << "\n" << o.err);
    CHECK((WIFEXITED(o.wait_status) && WEXITSTATUS(o.wait_status) == 1));
    CHECK(o.out.empty());
    CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
    CHECK(o.err.find("--max-seconds 0.1") != std::string::npos);
  }
  SECTION("Ctrl-C stops a long run with one line and no files") {
    const fs::path dir = scratch() / "interrupted";
    testing_support::RunOptions options;
    options.interrupt_after = 0.5;
    // 60 revolutions of RKF45 take about 6 s on this project's machine, so the signal lands mid-run on any
    // CI host (5 revolutions took 0.68 s here and finished before the signal on a faster CI host; the
    // fast method takes 0.2 s for all 60).
    const auto o = testing_support::run_bladestab({"transient", valid_scene, "--set", "model.terms=8", "--method", "rkf45",
                                                   "--revolutions", "60", "--out", dir.string(), "--chart", "none"},
                                                  options);
    INFO(o.command << "\n" << describe(o) << "\n" << o.err);
    CHECK((WIFEXITED(o.wait_status) && WEXITSTATUS(o.wait_status) == 130));
    CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
    CHECK(o.err.find("interrupted") != std::string::npos);
    CHECK((!fs::exists(dir) || fs::is_empty(dir)));  // a slow host may stop it before --out is made
  }
}

TEST_CASE("bad input: issue 11, scene files that never end (bad_input)", "[bad_input]") {
  testing_support::RunOptions quick;
  quick.timeout_seconds = 10;
  SECTION("/dev/zero") { expect_rejected({"modes", "/dev/zero"}, {"/dev/zero", "not a regular file", "character device"}, quick); }
  SECTION("a FIFO without a writer") {
    const std::string fifo = (scratch() / "scene.fifo").string();
    REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
    expect_rejected({"modes", fifo}, {fifo, "not a regular file", "FIFO"}, quick);
  }
  SECTION("a scene past 1 MiB") {
    const std::string big = (scratch() / "big.toml").string();
    std::ofstream(big) << read_text(valid_scene) << "\n# " << std::string(2 << 20, 'x') << "\n";
    expect_rejected({"modes", big}, {big, "at most 1048576"}, quick);
  }
}

TEST_CASE("bad input: issue 11, messages (bad_input)", "[bad_input][parallel]") {
  SECTION("a string with a newline is echoed escaped") {
    expect_rejected(modes({"--set", "model.basis=\"a\\nb\""}), {"model.basis = \"a\\nb\""});
  }
  SECTION("an array of 300 000 elements is echoed short") {
    std::string array = "[1";
    for (int k = 1; k < 300000; ++k) array += ", 1";
    const std::string path = edited_scene("big_array.toml", "model", "model = \"rayleigh\"\nratio = 0.01\nfrequencies_hz = " + array + "]");
    const auto o = expect_rejected({"modes", path}, {"damping.frequencies_hz = [1, 1, 1", "(300000 elements)"});
    CHECK(o.err.size() < 400);
  }
  SECTION("an empty option value is not 0") { expect_rejected(modes({"--count", ""}), {"--count ''", "integer >= 1"}); }
  SECTION("a pulse frequency of 1e308 is blamed on itself") {
    const auto o = expect_rejected({"stability", valid_scene, "--set", "load.pulse_frequency_hz=1e308"},
                                   {"load.pulse_frequency_hz = 1e+308", "(0, 1e8]"});
    CHECK(o.err.find("contact_time_rev") == std::string::npos);
  }
  SECTION("a pulse frequency too high for the contact names both keys") {
    expect_rejected({"stability", valid_scene, "--set", "load.pulse_frequency_hz=1e7"},
                    {"load.pulse_frequency_hz = 10000000", "load.contact_time_rev = 0.01", "outlasts"});
  }
  SECTION("a directory as the scene") {
    expect_rejected({"modes", scratch().string()}, {scratch().string(), "is a directory"});
  }
  SECTION("a missing scene says why") {
    expect_rejected({"modes", (scratch() / "nowhere.toml").string()}, {"nowhere.toml", "No such file or directory"});
  }
  SECTION("the unloaded blade's static instability names the blade's keys with the speed") {
    expect_rejected({"stability", valid_scene, "--set", "blade.length=1000"},
                    {"operation.speed_rad_s = 300", "blade.length = 1000", "statically unstable"});
  }
}

TEST_CASE("bad input: issue 11, options read alike (bad_input)", "[bad_input]") {
  SECTION("--cutoff-hz nan and -1 are refused by boundaries as by stability") {
    for (const std::string value : {"nan", "-1"}) {
      const auto b = expect_rejected({"boundaries", valid_scene, "--cutoff-hz", value}, {"--cutoff-hz " + value, "[0, 1e9]"});
      const auto s = expect_rejected({"stability", valid_scene, "--cutoff-hz", value}, {"--cutoff-hz " + value, "[0, 1e9]"});
      CHECK(b.err == s.err);
    }
  }
  SECTION("crosscheck --points '' does not run F = 0") {
    expect_rejected({"crosscheck", valid_scene, "--points", ""}, {"--points ''", "empty"});
  }
  SECTION("hex and padded numbers are refused everywhere") {
    expect_rejected(modes({"--count", "0x10"}), {"--count 0x10"});
    expect_rejected(modes({"--count", " 3"}), {"--count ' 3'"});
    expect_rejected({"stability", valid_scene, "--tolerance", "0x1p-20"}, {"--tolerance 0x1p-20"});
    expect_rejected({"boundaries", valid_scene, "--range", " 100:200"}, {"--range ' 100:200'"});
    expect_rejected(campbell(" 0:600:5"), {"--speeds ' 0:600:5'"});
    expect_rejected({"map", valid_scene, "--plane", "theta-fmax", "--resolution", " 4x4", "--chart", "none"},
                    {"--resolution ' 4x4'"});
  }
  SECTION("--name with a newline makes no such file") {
    const fs::path dir = scratch() / "names";
    expect_rejected({"transient", valid_scene, "--name", "a\nb", "--out", dir.string(), "--chart", "none"}, {"--name a\\nb"});
    CHECK((!fs::exists(dir) || fs::is_empty(dir)));
  }
}

TEST_CASE("bad input: issue 11, outputs (bad_input)", "[bad_input][parallel]") {
  const std::vector<std::string> tiny{"--set", "model.terms=4", "--count", "2", "--chart", "none"};
  SECTION("--out is checked before computing") {
    std::ofstream(scratch() / "a_file") << "x";
    expect_rejected({"campbell", valid_scene, "--speeds", "0:600:3", "--out", (scratch() / "a_file").string()},
                    {"--out", "a_file", "not a directory"});
  }
  SECTION("--out with a name the system refuses (a 300-character component) is refused before computing") {
    const std::string too_long = (scratch() / std::string(300, 'a') / "out").string();
    expect_rejected({"campbell", valid_scene, "--speeds", "0:600:3", "--out", too_long},
                    {"--out", "cannot write into it: File name too long"});
  }
  SECTION("a set that cannot be completed leaves no file of it") {
    const fs::path dir = scratch() / "blocked";
    fs::create_directories(dir / "campbell.json");  // the set's last file cannot be renamed into place
    std::vector<std::string> args{"campbell", valid_scene, "--speeds", "0:600:3", "--out", dir.string()};
    args.insert(args.end(), tiny.begin(), tiny.end());
    expect_rejected(args, {"campbell.json", "is a directory"});
    std::vector<std::string> left;
    for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename().string());
    CHECK(left == std::vector<std::string>{"campbell.json"});
  }
  SECTION("a failed write to stdout exits 1") {
    testing_support::RunOptions full;
    full.stdout_path = "/dev/full";
    const auto o = testing_support::run_bladestab(modes({"--count", "2"}), full);
    INFO(o.command << "\n" << describe(o) << "\n" << o.err);
    CHECK((WIFEXITED(o.wait_status) && WEXITSTATUS(o.wait_status) == 1));
    CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
    CHECK(o.err.find("stdout") != std::string::npos);
  }
}

TEST_CASE("bad input: issue 24, options read as the scene reads them (bad_input)", "[bad_input]") {
  SECTION("boundaries --max-order 0") {
    expect_rejected({"boundaries", valid_scene, "--max-order", "0"}, {"--max-order 0", "[1, 77]"});
  }
  SECTION("a repeated engine order is refused alike on the command line and in the scene") {
    const std::string rule = "must be a non-empty list of distinct integers, each in [1, 1000]";
    expect_rejected(campbell("0:600:10", {"--engine-orders", "1,1"}), {"--engine-orders 1,1", "1 is given twice", rule});
    expect_rejected(campbell("0:600:10", {"--engine-orders", "2", "--engine-orders", "2"}), {"--engine-orders 2,2", rule});
    const std::string scene = edited_scene("repeated_orders.toml", "", "",
                                           "[requirements]\nspeed_range_rad_s = [100.0, 200.0]\n"
                                           "engine_orders = [1, 1]\nfrequency_margin = 0.1\n");
    expect_rejected({"check", scene}, {"requirements.engine_orders = [1, 1]", rule});
  }
  SECTION("an unknown requirements key is named, not a known one reported missing") {
    const std::string scene = edited_scene("requirements_foo.toml", "", "", "[requirements]\nfoo = 3\n");
    expect_rejected({"check", scene}, {"requirements.foo = 3", "unknown key", "speed_range_rad_s"});
  }
  SECTION("a list option before the scene takes one word: the scene stays the scene") {
    // `--points 1 SCENE` had read "1,SCENE" ("SCENE is not allowed"), `--engine-orders 2 SCENE` alike.
    const testing_support::Outcome o = testing_support::run_bladestab({"campbell", "--engine-orders", "2", valid_scene, "--speeds", "0:400:5", "--chart",
                                     "none", "--format", "json"});
    INFO(o.err);
    CHECK(WIFEXITED(o.wait_status));
    CHECK(WEXITSTATUS(o.wait_status) == 0);
    CHECK(o.out.find("\"engine_orders\": [2]") != std::string::npos);
  }
  SECTION("crosscheck --points 1,1") {
    expect_rejected({"crosscheck", valid_scene, "--points", "1,1"},
                    {"--points 1,1", "1 is given twice", "distinct numbers, each in [0, 1000]"});
  }
  SECTION("a float for an integer key is echoed as a float") {
    expect_rejected(modes({"--set", "model.terms=16.0"}), {"model.terms = 16.0: must be an integer"});
    expect_rejected({"modes", edited_scene("terms_16.0.toml", "terms", "terms = 16.0")},
                    {"model.terms = 16.0: must be an integer"});
  }
  SECTION("--out with a component longer than a file name may be") {
    const std::string long_name(300, 'x');
    expect_rejected({"campbell", valid_scene, "--speeds", "0:600:3", "--out", (scratch() / long_name).string()},
                    {"--out", "cannot write into it", "File name too long"});
    expect_rejected({"map", valid_scene, "--plane", "theta-fmax", "--out", (scratch() / long_name / "m").string()},
                    {"--out", "cannot write into it", "File name too long"});
  }
  SECTION("each --set takes one override: the scene path after two of them is the scene") {
    const testing_support::Outcome o = testing_support::run_bladestab(
        {"modes", "--set", "model.terms=5", "--set", "operation.speed_rad_s=0", valid_scene, "--count", "1", "--format", "json"});
    INFO(o.command << ": " << describe(o) << "\n" << o.err);
    REQUIRE(WIFEXITED(o.wait_status));
    REQUIRE(WEXITSTATUS(o.wait_status) == 0);
    const testing_support::Json j = testing_support::parse_json(o.out);
    CHECK(j["model"]["terms"].number == 5);
    CHECK(j["speed_rad_s"].number == 0);
    expect_rejected({"modes", valid_scene, "--set", "model.terms=5", "operation.speed_rad_s=0"},
                    {"operation.speed_rad_s=0", "give each override its own --set section.key=value"});
  }
  SECTION("a modal cut-off below the first mode keeps no mode: refused, with the first mode's frequency") {
    expect_rejected({"stability", valid_scene, "--cutoff-hz", "0.5"}, {"--cutoff-hz 0.5", "at or below the first mode, ", " Hz at operation.speed_rad_s = 300"});
    expect_rejected({"boundaries", valid_scene, "--cutoff-hz", "0.5"}, {"--cutoff-hz 0.5", "at or below the first mode, ", " Hz at operation.speed_rad_s = 300"});
    expect_rejected(modes({"--set", "model.reduction=modal", "--set", "model.cutoff_hz=0.5"}),
                    {"model.cutoff_hz = 0.5", "at or below the first mode, ", " Hz at operation.speed_rad_s = 300"});
  }
}

TEST_CASE("bad input: sweep options and the static tip compression (bad_input)", "[bad_input][sweep][parallel]") {
  const auto sweep = [](const std::string& key, const std::string& values, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"sweep", valid_scene, "--key", key, "--values", values, "--out", scratch().string(),
                                  "--chart", "none"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  SECTION("unknown key") {
    expect_rejected(sweep("blade.colour", "0:1:3"), {"--key blade.colour", "unknown key", "slenderness"});
  }
  SECTION("unknown section") {
    expect_rejected(sweep("rotor.blades", "1:3:3"), {"--key rotor.blades", "[rotor]", "unknown section"});
  }
  SECTION("a key without a section") {
    expect_rejected(sweep("slenderness", "0.01:0.1:3"), {"--key slenderness", "section.key"});
  }
  SECTION("a key that takes no number") {
    expect_rejected(sweep("model.basis", "0:1:3"), {"--key model.basis", "takes no number", "\"legendre\""});
  }
  SECTION("a key the scene does not use") {
    expect_rejected(sweep("damping.ratio", "0:0.1:3"), {"--key damping.ratio", "not used with damping.model"});
  }
  SECTION("empty range") { expect_rejected(sweep("blade.slenderness", "0.01:0.01:5"), {"--values 0.01:0.01:5", "start != stop"}); }
  SECTION("a single value") { expect_rejected(sweep("blade.slenderness", "0.01:0.1:1"), {"--values 0.01:0.1:1", "count in [2, 100000]"}); }
  SECTION("NaN") { expect_rejected(sweep("blade.slenderness", "nan:0.1:5"), {"--values nan:0.1:5", "finite"}); }
  SECTION("values not a range") { expect_rejected(sweep("blade.slenderness", "0.01,0.1"), {"--values 0.01,0.1", "start:stop:count"}); }
  SECTION("a value the key does not allow") {
    expect_rejected(sweep("blade.slenderness", "0.5:1.5:3"), {"--values 0.5:1.5:3", "blade.slenderness = 1:", "[1e-4, 1)"});
  }
  SECTION("an integer key between integers") {
    expect_rejected(sweep("model.terms", "4:9:3"), {"--values 4:9:3", "model.terms = 6.5", "integer"});
  }
  SECTION("--count 0") { expect_rejected(sweep("blade.slenderness", "0.01:0.1:3", {"--count", "0"}), {"--count 0", ">= 1"}); }
  SECTION("missing --key") {
    expect_rejected({"sweep", valid_scene, "--values", "0:1:3"}, {"--key", "required"});
  }
  SECTION("a negative static compression") {
    expect_rejected(modes({"--set", "operation.tip_compression_over_fcr=-0.5"}),
                    {"operation.tip_compression_over_fcr = -0.5", "[0, 1000)"});
  }
  SECTION("a non-finite static compression") {
    expect_rejected(modes({"--set", "operation.tip_compression_over_fcr=inf"}),
                    {"operation.tip_compression_over_fcr = inf", "finite"});
  }
  SECTION("a static compression that buckles the blade") {
    expect_rejected(modes({"--set", "operation.speed_rad_s=0", "--set", "operation.tip_compression_over_fcr=1"}),
                    {"operation.tip_compression_over_fcr = 1", "statically unstable", "buckles at 0.9992"});
  }
  SECTION("... in every command") {
    for (const std::string command : {"campbell", "stability", "boundaries", "map", "transient", "crosscheck"}) {
      std::vector<std::string> args{command, valid_scene, "--set", "operation.tip_compression_over_fcr=50"};
      if (command == "campbell") args.insert(args.end(), {"--speeds", "0:300:3", "--out", scratch().string(), "--chart", "none"});
      if (command == "map") args.insert(args.end(), {"--plane", "theta-fmax", "--out", scratch().string(), "--chart", "none"});
      if (command == "transient") args.insert(args.end(), {"--chart", "none", "--out", scratch().string()});
      DYNAMIC_SECTION(command) { expect_rejected(args, {"operation.tip_compression_over_fcr = 50", "statically unstable"}); }
    }
  }
}
