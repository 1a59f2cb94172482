// A fixed corpus of hostile command lines, run through the real program: every scene key given
// values outside every allowed range or of the wrong kind, every numeric option given malformed or
// extreme text, and scene files that are not scene files, spread over all eight commands. Each must
// be refused the input-error way (tests/support/run_cli.hpp): exit 2, nothing on stdout, one line
// on stderr naming the key, option or file — never a crash, a hang, a NaN or a multi-line error.
// The corpus is generated here, deterministically; scripts/fuzz.py runs random campaigns beyond it.
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>

#include <catch2/catch.hpp>

#include "support/run_cli.hpp"

namespace {

using testing_support::expect_rejected;
using testing_support::RunOptions;
using testing_support::scratch;

const std::string scene = BLADESTAB_SOURCE_DIR "/stability_maps/sinha2005/blade.toml";

struct FuzzCase {
  std::vector<std::string> args;
  std::string named;  // must occur in the error line: the key, the option or the file
};

// The eight commands, each with the least it needs and its outputs in the scratch directory.
std::vector<std::string> command_line(int which, const std::string& scene_path) {
  const std::string out = (scratch() / "fuzz_out").string();
  switch (which % 8) {
    case 0: return {"modes", scene_path};
    case 1: return {"campbell", scene_path, "--speeds", "0:600:3", "--out", out, "--chart", "none"};
    case 2: return {"stability", scene_path};
    case 3: return {"boundaries", scene_path};
    case 4: return {"map", scene_path, "--plane", "theta-fmax", "--out", out, "--chart", "none"};
    case 5: return {"transient", scene_path, "--out", out, "--chart", "none"};
    case 6: return {"crosscheck", scene_path};
    default: return {"sweep", scene_path, "--key", "operation.speed_rad_s", "--values", "0:300:2", "--out", out, "--chart", "none"};
  }
}

// Scene keys with what they need to be read at all (damping.ratio only with a damping model, …).
struct Key {
  std::string name;
  std::vector<std::string> context;  // --set assignments first
};

std::vector<FuzzCase> scene_key_cases() {
  const std::vector<std::string> modal{"damping.model=modal", "damping.ratio=0.01"};
  const std::vector<std::string> rayleigh{"damping.model=rayleigh", "damping.ratio=0.01", "damping.frequencies_hz=[50, 2000]"};
  const std::vector<std::string> clearance{"load.mode=clearance", "load.intrusion=1e-3"};
  const std::vector<Key> numbers{
      {"blade.length", {}}, {"blade.hub_radius", {}}, {"blade.area", {}}, {"blade.slenderness", {}},
      {"blade.youngs_modulus", {}}, {"blade.density", {}}, {"blade.poisson", {}}, {"blade.shear_coefficient", {}},
      {"blade.stagger_deg", {}}, {"operation.speed_rad_s", {}}, {"load.fmax_over_fcr", {}},
      {"load.contact_time_rev", {}}, {"load.friction", {}}, {"load.clearance", {}}, {"load.pulse_frequency_hz", {}},
      {"damping.ratio", modal}, {"damping.frequencies_hz", rayleigh}, {"model.cutoff_hz", {"model.reduction=modal"}},
      {"load.intrusion", clearance}, {"load.contact_stiffness", clearance},
      {"operation.tip_compression_over_fcr", {}}};
  // Outside every key's range, or not a number at all ("a\nb" is a string holding a newline).
  const std::vector<std::string> bad_numbers{"nan", "inf", "-inf", "1e308", "-1e308", "9e99", "-9e99", "\"x\"",
                                             "[1, 2]", "true", "{ a = 1 }", "1979-05-27", "\"a\\nb\""};
  const std::vector<Key> integers{{"model.terms", {}}, {"model.reduction_vectors", {}}, {"load.pulses_per_rev", {}},
                                  {"load.pulse_count", {}}};
  const std::vector<std::string> bad_integers{"2.5", "-1", "99999999999", "nan", "\"x\"", "[1]", "true"};
  const std::vector<Key> choices{{"model.basis", {}},    {"model.theory", {}},       {"model.reduction", {}},
                                 {"damping.model", {}},  {"load.profile", {}},       {"load.approximation", {}},
                                 {"load.mode", {}},      {"model.axial", {}},        {"model.coriolis", {}}};
  const std::vector<std::string> bad_choices{"\"nope\"", "1", "[\"sine\"]", "\"SINE\"", ""};

  std::vector<FuzzCase> cases;
  const auto add = [&](const Key& key, const std::string& value) {
    FuzzCase c{command_line(static_cast<int>(cases.size()), scene), key.name};
    for (const std::string& assignment : key.context) c.args.insert(c.args.end(), {"--set", assignment});
    c.args.insert(c.args.end(), {"--set", key.name + "=" + value});
    cases.push_back(c);
  };
  for (const Key& key : numbers) {
    for (const std::string& v : bad_numbers) {
      // Two numbers are what damping.frequencies_hz wants: two equal ones it refuses.
      add(key, key.name == "damping.frequencies_hz" && v == "[1, 2]" ? "[2, 2]" : v);
    }
  }
  for (const std::string& v : {"[nan, 1]", "[1e-300, 2e-300]", "[1, 1e308]", "[1]", "[1, 2, 3]"}) add(numbers[16], v);
  for (const Key& key : integers) {
    for (const std::string& v : bad_integers) add(key, v);
  }
  for (const Key& key : choices) {
    for (const std::string& v : bad_choices) add(key, v);
  }
  return cases;
}

std::vector<FuzzCase> option_cases() {
  struct Option {
    int command;  // as command_line
    std::string name;
    std::vector<std::string> context;  // other options it needs
  };
  const std::vector<Option> options{
      {0, "--count", {}}, {0, "--tolerance", {}}, {0, "--max-seconds", {}}, {0, "--max-memory", {}},
      {1, "--count", {}}, {1, "--tolerance", {}}, {1, "--engine-orders", {}}, {1, "--speeds", {}},
      {2, "--harmonics", {}}, {2, "--tolerance", {}}, {2, "--cutoff-hz", {}}, {2, "--max-seconds", {}},
      {3, "--approximation", {}}, {3, "--tolerance", {}}, {3, "--at-theta", {}}, {3, "--cutoff-hz", {}},
      {3, "--max-order", {}}, {3, "--range", {}},
      {4, "--trace", {}}, {4, "--engine-order", {}}, {4, "--approximation", {}}, {4, "--max-order", {}},
      {4, "--tolerance", {}}, {4, "--threads", {}}, {4, "--resolution", {}}, {4, "--theta", {}}, {4, "--fmax", {}},
      {4, "--max-memory", {}},
      {5, "--revolutions", {}}, {5, "--tolerance", {}}, {5, "--samples-per-rev", {}},
      {5, "--steps-per-period", {"--step", "fixed"}},
      {6, "--points", {}}, {6, "--revolutions", {}},
      {7, "--values", {}}, {7, "--count", {}}, {7, "--max-seconds", {}}};
  // Empty, padded, hex, not finite, beyond any range, not a number, a list where one is wanted.
  const std::vector<std::string> bad_values{"", " 1", "1 ", "0x10", "nan", "inf", "1e999", "-1e308", "abc", "1e308"};
  std::vector<FuzzCase> cases;
  for (const Option& o : options) {
    for (const std::string& v : bad_values) {
      FuzzCase c{command_line(o.command, scene), o.name};
      c.args.insert(c.args.end(), o.context.begin(), o.context.end());
      c.args.insert(c.args.end(), {o.name, v});
      cases.push_back(c);
    }
  }
  // The speed plane's grid, and the transient's file stem (any of these would name odd files).
  for (const std::string& v : {"", "-1:5:3", "0:600:3", "1e308:1e309:3", "5:1:3"}) {
    cases.push_back({{"map", scene, "--plane", "speed-fmax", "--out", (scratch() / "fuzz_out").string(), "--chart",
                      "none", "--speeds", v},
                     "--speeds"});
  }
  for (const std::string& v : std::vector<std::string>{"", "a/b", "a\nb", "-x", ".hidden", "a b", "x\\y", "a\"b", std::string(300, 'n')}) {
    for (const int which : {5, 7}) {
      std::vector<std::string> args = command_line(which, scene);
      args.insert(args.end(), {"--name", v});
      cases.push_back({args, "--name"});
    }
  }
  return cases;
}

// Scene files that are not scene files: the path must be named.
std::vector<FuzzCase> file_cases() {
  const auto write = [](const std::string& name, const std::string& text) {
    const std::string path = (scratch() / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  };
  std::string garbage;
  for (unsigned x = 12345, k = 0; k < 4096; ++k) garbage += static_cast<char>((x = x * 1103515245 + 12345) >> 16);
  const std::string valid = testing_support::read_text(scene);
  const std::string fifo = (scratch() / "fifo.toml").string();
  mkfifo(fifo.c_str(), 0600);
  const std::vector<std::string> paths{
      scratch().string(),
      fifo,
      "/dev/zero",
      (scratch() / "missing.toml").string(),
      write("empty.toml", ""),
      write("garbage.toml", garbage),
      write("nul.toml", valid.substr(0, 100) + std::string(1, '\0') + valid.substr(100)),
      write("huge.toml", valid + "\n#" + std::string(2 << 20, 'x') + "\n"),
      write("duplicate.toml", valid + "\n[blade]\nlength = 1\n"),
      write("truncated.toml", valid.substr(0, valid.size() / 2)),
  };
  std::vector<FuzzCase> cases;
  for (std::size_t k = 0; k < paths.size(); ++k) {
    cases.push_back({command_line(static_cast<int>(k), paths[k]), paths[k]});
  }
  return cases;
}

void run(const std::vector<FuzzCase>& cases) {
  RunOptions options;
  options.timeout_seconds = 30;  // a case that passed validation would compute for much longer
  for (const FuzzCase& c : cases) expect_rejected(c.args, {c.named}, options);
}

}  // namespace

TEST_CASE("fuzz: the corpus has the size the suite promises", "[fuzz]") {
  CHECK(scene_key_cases().size() + option_cases().size() + file_cases().size() >= 300);
}

TEST_CASE("fuzz: hostile scene values over all commands", "[fuzz][long_under_sanitizers]") { run(scene_key_cases()); }

TEST_CASE("fuzz: hostile option values over all commands", "[fuzz][long_under_sanitizers]") { run(option_cases()); }

TEST_CASE("fuzz: scene files that are not scene files", "[fuzz]") { run(file_cases()); }
