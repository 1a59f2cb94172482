#pragma once
// A scene: one TOML file describing a blade, how it is modelled, how it runs and how it is loaded.
// All values are SI. `load_scene` reads and validates it; every key can be overridden with
// "section.key=value" strings.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace bladestab {

// One station of a blade's section table (docs/theory.md §9), SI units; properties are linear
// between stations.
struct SectionStation {
  double span_fraction = 0;      // s/L: 0 at the root … 1 at the tip
  double area = 0;               // A [m^2]
  double i_flap = 0;             // I₁ [m^4], minor principal inertia: bending normal to the chord
  double i_edge = 0;             // I₂ [m^4], major: bending along the chord; I₂ ≥ I₁
  double twist_deg = 0;          // structural twist, added to the stagger: β(s) = β_root + twist
  double youngs_modulus = 0;     // E [Pa] (the table's column, else blade.youngs_modulus)
  double density = 0;            // ρ [kg/m^3] (else blade.density)
  double shear_coefficient = 0;  // κ (else blade.shear_coefficient)
};

struct BladeSpec {
  double length = 0;             // L [m]
  double hub_radius = 0;         // r [m]
  double area = 0;               // A [m^2]
  double inertia = 0;            // I [m^4]; from `slenderness` d̄ when given (I = d̄² A L², docs/theory.md §3)
  double youngs_modulus = 0;     // E [Pa]
  double density = 0;            // ρ [kg/m^3]
  double poisson = 0;            // ν
  double shear_coefficient = 0;  // κ
  double stagger_deg = 0;        // β [deg]
  // A section table (blade.sections = "FILE.csv" or [[blade.section]]): the blade of docs/theory.md
  // §9, bending in two planes. Empty: the uniform blade of §1–2, bending in one plane. With a table,
  // area and inertia above are the root station's (the scales of Λ and d̄).
  std::vector<SectionStation> sections;
  double twist_scale = 1;        // blade.twist_scale: multiplies every station's twist
  bool two_planes() const { return !sections.empty(); }
};

enum class BasisKind { sine, legendre };
enum class BeamTheory { timoshenko, euler_bernoulli };

// How the periodic system is reduced before time integration (reduction.hpp, docs/theory.md §6).
enum class ReductionKind { automatic, modal, none };

struct ReductionSpec {
  ReductionKind kind = ReductionKind::automatic;
  int vectors = 0;       // automatic: modes per load level; 0 = chosen to meet the tolerance
  double cutoff_hz = 0;  // modal: keep the unloaded modes below this frequency (0: all)
};

struct ModelSpec {
  BasisKind basis = BasisKind::legendre;
  int terms = 0;  // shape functions per field
  BeamTheory theory = BeamTheory::timoshenko;
  bool axial = true;
  bool coriolis = true;
  ReductionSpec reduction;  // optional keys reduction, reduction_vectors, cutoff_hz
};

struct OperationSpec {
  double speed_rad_s = 0;  // Ω
  // Optional: a static compressive tip load F_a = tip_compression_over_fcr · F_cr, F_cr = π²EI/(4L²)
  // (compression positive; Sinha's Fig. 9). It enters the stiffness through the geometric matrix,
  // K_S − F_a G, and the steady load through the tip (model.hpp).
  double tip_compression_over_fcr = 0;
};

enum class DampingModel { none, modal, rayleigh, paper };

struct DampingSpec {
  DampingModel model = DampingModel::none;
  double ratio = 0;                    // ζ
  std::vector<double> frequencies_hz;  // rayleigh: the two frequencies that get ratio ζ exactly
  bool damped() const { return model != DampingModel::none; }
};

// The paper's damping C_D = (2ζ/Ω) K_S (37) needs a speed Ω > 0: InputError naming damping.model and
// `speed_name` (the scene's operation.speed_rad_s, or a speed an analysis asks for) otherwise.
void check_damping_speed(const DampingSpec& damping, double speed_rad_s, const std::string& speed_name);

enum class PulseProfile { half_sine, cosine, triangular, sawtooth, rectangular, impulse };
enum class LoadApproximation { cosine, fourier, exact };
enum class LoadMode { force, clearance };

struct LoadSpec {
  PulseProfile profile = PulseProfile::half_sine;
  double fmax_over_fcr = 0;    // F̄_max = F_max / F_cr
  double contact_time_rev = 0; // t̄_c = t_c Ω / 2π
  int pulses_per_rev = 1;
  int pulse_count = 0;         // 0: endless train
  LoadApproximation approximation = LoadApproximation::cosine;
  LoadMode mode = LoadMode::force;
  double friction = 0;         // μ
  double clearance = 0;        // δ [m]: casing to tip at the steady rotating equilibrium
  // clearance mode: depth of the casing's local distortion [m], shaped like the pulse profile over
  // contact_time_rev, met pulses_per_rev times a revolution; and the penalty stiffness of the wall
  // [N/m] (default: 100 times the blade's static axial stiffness at the tip)
  double intrusion = 0;
  std::optional<double> contact_stiffness;
  std::optional<double> pulse_frequency_hz;  // default: pulses_per_rev · Ω / 2π
};

// Optional [requirements]: what a blade design must meet over its operating range, for
// `bladestab check` (requirements_check.hpp). Every other command ignores it.
struct RequirementsSpec {
  double speed_lo_rad_s = 0, speed_hi_rad_s = 0;  // the operating range, lo < hi
  std::vector<int> engine_orders{1, 2, 3, 4, 5, 6};
  // |f − kΩ/2π| ≥ frequency_margin · f for every mode f and engine order k inside the range.
  std::optional<double> frequency_margin;
  // Stable for every rub load F̄_max ∈ [0, max_fmax_over_fcr] inside the range (θ = pulses_per_rev · Ω).
  std::optional<double> max_fmax_over_fcr;
};

struct Scene {
  std::string source;  // file name, for messages
  BladeSpec blade;
  ModelSpec model;
  OperationSpec operation;
  DampingSpec damping;
  LoadSpec load;
  std::optional<RequirementsSpec> requirements;
};

// Reads `path`, applies `overrides` ("section.key=value", value in TOML syntax or a bare word),
// validates everything. Throws InputError with a one-line message on any problem.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// The text of a scene file: a regular file of at most max_scene_bytes; InputError saying why not.
inline constexpr std::size_t max_scene_bytes = 1 << 20;
std::string read_scene_file(const std::string& path);

// Same as load_scene, from TOML text (used by tests, by scenes built in code and by sweeps that read
// one file with many overrides).
Scene parse_scene(const std::string& toml_text, const std::string& source_name,
                  const std::vector<std::string>& overrides = {});

// The scene at an operating point: rotor speed Ω [rad/s], pulse frequency θ [rad/s] and peak load
// F̄ = F_max / F_cr; everything else as in `scene`.
Scene scene_at(Scene scene, double speed_rad_s, double theta_rad_s, double fmax_over_fcr);

const char* to_string(BasisKind);
const char* to_string(BeamTheory);
const char* to_string(DampingModel);
const char* to_string(PulseProfile);
const char* to_string(ReductionKind);
const char* to_string(LoadApproximation);

}  // namespace bladestab
