// Scene reading and validation. Every problem becomes one InputError line of the form
//   "<file>: <section>.<key> = <value>: <what is allowed>"
#include "bladestab/scene/scene.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "support/message_text.hpp"
#include "bladestab/scene/scene_limits.hpp"
#include "scene/scene_override.hpp"
#include "scene/section_table.hpp"

namespace bladestab {
namespace {

namespace limits = scene_limits;

// Paths are echoed longer than values: the directory is part of what the user needs to see.
constexpr std::size_t max_path_shown = 240;

// Each choice's names in the scene file, read by SectionReader::choice and written by to_string.
template <class Enum>
using Names = std::vector<std::pair<std::string, Enum>>;
const Names<BasisKind> basis_names{{"sine", BasisKind::sine}, {"legendre", BasisKind::legendre}};
const Names<BeamTheory> theory_names{{"timoshenko", BeamTheory::timoshenko},
                                     {"euler-bernoulli", BeamTheory::euler_bernoulli}};
const Names<ReductionKind> reduction_names{
    {"auto", ReductionKind::automatic}, {"modal", ReductionKind::modal}, {"none", ReductionKind::none}};
const Names<DampingModel> damping_names{{"none", DampingModel::none},
                                        {"modal", DampingModel::modal},
                                        {"rayleigh", DampingModel::rayleigh},
                                        {"paper", DampingModel::paper}};
const Names<PulseProfile> profile_names{{"half-sine", PulseProfile::half_sine},
                                        {"cosine", PulseProfile::cosine},
                                        {"triangular", PulseProfile::triangular},
                                        {"saw-tooth", PulseProfile::sawtooth},
                                        {"rectangular", PulseProfile::rectangular},
                                        {"impulse", PulseProfile::impulse}};
const Names<LoadApproximation> approximation_names{{"cosine", LoadApproximation::cosine},
                                                   {"fourier", LoadApproximation::fourier},
                                                   {"exact", LoadApproximation::exact}};
const Names<LoadMode> mode_names{{"force", LoadMode::force}, {"clearance", LoadMode::clearance}};

template <class Enum>
const char* name_of(const Names<Enum>& names, Enum value) {
  for (const auto& [name, v] : names) {
    if (v == value) return name.c_str();
  }
  return "?";
}

// Appends `node` in TOML-like form, arrays and inline tables on one line, stopping once `out`
// passes `limit` characters (an array may have a million elements).
void append_shown(const toml::node& node, std::string& out, std::size_t limit) {
  if (const auto* text = node.as_string()) {
    out += '"' + text->get() + '"';
  } else if (const auto* number = node.as_floating_point()) {
    // As TOML writes a float: with its point (16.0), so that it does not read as the integer 16.
    const std::string text = fmt::format("{}", number->get());
    out += text.find_first_of(".eEn") == std::string::npos ? text + ".0" : text;
  } else if (const auto* array = node.as_array()) {
    out += '[';
    for (std::size_t i = 0; i < array->size(); ++i) {
      if (out.size() > limit) {
        out += fmt::format("… ({} elements)", array->size());
        break;
      }
      out += i == 0 ? "" : ", ";
      append_shown(*array->get(i), out, limit);
    }
    out += ']';
  } else if (const auto* table = node.as_table()) {
    out += '{';
    bool first = true;
    for (const auto& [key, value] : *table) {
      if (out.size() > limit) {
        out += "…";
        break;
      }
      out += (first ? "" : ", ") + std::string(key.str()) + " = ";
      first = false;
      append_shown(value, out, limit);
    }
    out += '}';
  } else {
    std::ostringstream other;  // integers, booleans, dates
    node.visit([&other](auto&& v) { other << v; });
    out += other.str();
  }
}

// A value as messages echo it: on one line and short.
std::string show(const toml::node& node) {
  constexpr std::size_t limit = 60;
  std::string out;
  append_shown(node, out, limit);
  return echoed(out, 2 * limit);
}

// Reads the keys of one [section], remembering which were used so the rest can be reported as
// unknown.
class SectionReader {
public:
  using Reason = SceneKeyError::Reason;

  SectionReader(const toml::table& root, std::string section, std::string source)
      : section_(std::move(section)), source_(std::move(source)) {
    const toml::node* node = root.get(section_);
    if (node == nullptr) fail_plain(fmt::format("[{}]: missing section", section_));
    table_ = node->as_table();
    if (table_ == nullptr) fail_plain(fmt::format("{}: must be a [{}] table", section_, section_));
  }

  bool has(const std::string& key) const { return table_->contains(key); }

  // A key read by someone else (a table of tables): known and used.
  void mark_used(const std::string& key) {
    known_.insert(key);
    used_.insert(key);
  }

  // A number in `allowed`; `meaning` names the quantity and its unit for the message.
  double number(const std::string& key, const AllowedRange& allowed, const std::string& meaning) {
    const toml::node& node = require(key);
    const std::string what = fmt::format("must be a finite number in {} ({})", allowed.text(), meaning);
    std::optional<double> value;
    if (node.is_floating_point()) value = node.as_floating_point()->get();
    if (node.is_integer()) value = static_cast<double>(node.as_integer()->get());
    if (!value || !std::isfinite(*value) || !allowed.contains(*value)) fail(key, node, what);
    return *value;
  }

  std::optional<double> optional_number(const std::string& key, const AllowedRange& allowed,
                                        const std::string& meaning) {
    known_.insert(key);  // named among the section's keys in a message, given or not
    if (!has(key)) return std::nullopt;
    return number(key, allowed, meaning);
  }

  int integer(const std::string& key, long lo, long hi) {
    const toml::node& node = require(key);
    if (!node.is_integer()) fail(key, node, "must be an integer");
    const long value = static_cast<long>(node.as_integer()->get());
    if (value < lo || value > hi) fail(key, node, fmt::format("must be an integer in [{}, {}]", lo, hi));
    return static_cast<int>(value);
  }

  bool boolean(const std::string& key) {
    const toml::node& node = require(key);
    if (!node.is_boolean()) fail(key, node, "must be true or false", Reason::not_numeric);
    return node.as_boolean()->get();
  }

  template <class Enum>
  Enum choice(const std::string& key, const Names<Enum>& table) {
    const std::map<std::string, Enum> options(table.begin(), table.end());  // listed in alphabetical order
    const toml::node& node = require(key);
    std::string names;
    for (const auto& [name, unused] : options) names += (names.empty() ? "" : ", ") + fmt::format("\"{}\"", name);
    if (!node.is_string()) fail(key, node, "must be one of " + names, Reason::not_numeric);
    const auto it = options.find(node.as_string()->get());
    if (it == options.end()) fail(key, node, "must be one of " + names);
    return it->second;
  }

  std::vector<double> number_list(const std::string& key, std::size_t count, const AllowedRange& allowed,
                                  const std::string& meaning) {
    const toml::node& node = require(key);
    const toml::array* array = node.as_array();
    const std::string what = fmt::format("must be a list of {} finite numbers, each in {} ({})", count,
                                         allowed.text(), meaning);
    if (array == nullptr) fail(key, node, what, Reason::not_numeric);
    if (array->size() != count) fail(key, node, what);
    std::vector<double> values;
    for (const toml::node& item : *array) {
      std::optional<double> v;
      if (item.is_floating_point()) v = item.as_floating_point()->get();
      if (item.is_integer()) v = static_cast<double>(item.as_integer()->get());
      if (!v || !std::isfinite(*v) || !allowed.contains(*v)) fail(key, node, what);
      values.push_back(*v);
    }
    return values;
  }

  // A non-empty list of distinct integers, each in [lo, hi] (allowed_range.hpp).
  std::vector<int> distinct_integer_list(const std::string& key, long lo, long hi, const std::string& meaning) {
    const toml::node& node = require(key);
    const toml::array* array = node.as_array();
    const std::string what = fmt::format("{} ({})", distinct_integers_rule(lo, hi), meaning);
    if (array == nullptr) fail(key, node, what, Reason::not_numeric);
    if (array->empty()) fail(key, node, what);
    std::vector<double> values;
    for (const toml::node& item : *array) {
      if (!item.is_integer()) fail(key, node, what);
      const long v = static_cast<long>(item.as_integer()->get());
      if (v < lo || v > hi) fail(key, node, what);
      values.push_back(static_cast<double>(v));
    }
    if (first_repeat(values)) fail(key, node, what);
    return std::vector<int>(values.begin(), values.end());
  }

  // Reports keys that were present but never read: unknown ones, and known ones that the other
  // settings make meaningless (`unused_because` says which setting).
  void reject_unknown(const std::string& unused_because = "") const {
    for (const auto& [key, node] : *table_) {
      const std::string name(key.str());
      if (used_.count(name) == 0 && known_.count(name) != 0) {
        fail_key(name, Reason::unused,
                 fmt::format("{}.{} = {}: not used with {}", section_, name, show(node), unused_because));
      }
      if (used_.count(name) == 0) fail_unknown(name, node);
    }
  }

  // Keys the section does not know at all, before any of its known keys is read (so that a
  // misspelt key is named, not the known one it was meant as, reported missing).
  void reject_unknown_names() const {
    for (const auto& [key, node] : *table_) {
      if (known_.count(std::string(key.str())) == 0) fail_unknown(std::string(key.str()), node);
    }
  }

  void known(std::initializer_list<const char*> keys) {
    for (const char* k : keys) known_.insert(k);
  }

  // A value the key does not take: of the wrong kind for a key that takes no number
  // (not_numeric), else not allowed.
  [[noreturn]] void fail(const std::string& key, const toml::node& node, const std::string& what,
                         Reason reason = Reason::not_allowed) const {
    fail_key(key, reason, fmt::format("{}.{} = {}: {}", section_, key, show(node), what));
  }
  [[noreturn]] void fail_both(const std::string& a, const std::string& b, const std::string& what) const {
    fail_plain(fmt::format("{0}.{1} = {2} and {0}.{3} = {4}: {5}", section_, a, show(*table_->get(a)), b,
                           show(*table_->get(b)), what));
  }
  // A value that is in range by itself but not in what it gives with the others.
  [[noreturn]] void fail_derived(const std::string& key, const std::string& what) const {
    fail(key, *table_->get(key), what);
  }
  [[noreturn]] void fail_missing(const std::string& key, const std::string& what) const {
    fail_plain(fmt::format("{}.{}: missing; {}", section_, key, what));
  }

private:
  const toml::node& require(const std::string& key) {
    known_.insert(key);
    const toml::node* node = table_->get(key);
    if (node == nullptr) fail_missing(key, "required");
    used_.insert(key);
    return *node;
  }

  [[noreturn]] void fail_plain(const std::string& message) const {
    throw InputError(fmt::format("{}: {}", source_, message));
  }
  [[noreturn]] void fail_unknown(const std::string& name, const toml::node& node) const {
    std::string allowed;
    for (const auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
    fail_key(name, Reason::unknown, fmt::format("{}.{} = {}: unknown key (known in [{}]: {})", section_, echoed(name),
                                                show(node), section_, allowed));
  }
  [[noreturn]] void fail_key(const std::string& key, Reason reason, const std::string& message) const {
    throw SceneKeyError(fmt::format("{}: {}", source_, message), section_ + "." + key, reason);
  }

  std::string section_;
  std::string source_;
  const toml::table* table_ = nullptr;
  std::set<std::string> used_;
  std::set<std::string> known_;
};

// The optional [requirements] of `bladestab check`: each key optional, but a margin or a load.
RequirementsSpec read_requirements(const toml::table& root, const std::string& source) {
  SectionReader section(root, "requirements", source);
  section.known({"speed_range_rad_s", "engine_orders", "frequency_margin", "max_fmax_over_fcr"});
  section.reject_unknown_names();
  RequirementsSpec r;
  if (!section.has("speed_range_rad_s")) {
    section.fail_missing("speed_range_rad_s", "the operating range [lo, hi] in rad/s is required");
  }
  const std::vector<double> range = section.number_list("speed_range_rad_s", 2, limits::speed_rad_s,
                                                        "operating range [lo, hi] in rad/s, lo < hi");
  if (!(range[0] < range[1])) {
    section.fail_derived("speed_range_rad_s", "must be [lo, hi] with lo < hi (the operating range in rad/s)");
  }
  r.speed_lo_rad_s = range[0];
  r.speed_hi_rad_s = range[1];
  if (section.has("engine_orders")) {
    r.engine_orders = section.distinct_integer_list("engine_orders", 1, limits::max_engine_order,
                                                    "engine orders k of the lines f = kΩ/2π");
  }
  r.frequency_margin = section.optional_number(
      "frequency_margin", limits::frequency_margin, "least |f − kΩ/2π| / f inside the range");
  r.max_fmax_over_fcr = section.optional_number(
      "max_fmax_over_fcr", limits::max_fmax_over_fcr, "largest rub load F_max / F_cr that must be stable");
  if (!r.frequency_margin && !r.max_fmax_over_fcr) {
    section.fail_missing("frequency_margin",
                         "give requirements.frequency_margin, requirements.max_fmax_over_fcr or both");
  }
  section.reject_unknown();
  return r;
}

// Every top-level table is a known section.
void check_sections(const toml::table& root, const std::string& source) {
  for (const auto& [key, node] : root) {
    static const std::set<std::string> sections{"blade", "model", "operation", "damping", "load", "requirements"};
    if (sections.count(std::string(key.str())) == 0) {
      throw SceneKeyError(fmt::format("{}: [{}]: unknown section (known: blade, model, operation, damping, load, "
                                      "requirements)",
                                      source, echoed(key.str())),
                          std::string(key.str()), SceneKeyError::Reason::unknown);
    }
  }
}

// area and inertia of a uniform blade; with a section table, its root station's.
void read_uniform_section(SectionReader& blade, BladeSpec& b) {
  b.area = blade.number("area", limits::area_m2, "cross-section area in m^2");
  if (!blade.has("slenderness") && !blade.has("inertia")) {
    blade.fail_missing("slenderness", "give exactly one of blade.slenderness (d̄) and blade.inertia (I in m^4)");
  }
  if (blade.has("slenderness") && blade.has("inertia")) {
    blade.fail_both("slenderness", "inertia", "give exactly one of them (I = d̄² A L²)");
  }
  if (blade.has("slenderness")) {
    const double d = blade.number("slenderness", limits::slenderness, "d̄ = sqrt(I/(A L²))");
    b.inertia = d * d * b.area * b.length * b.length;  // docs/theory.md §3: d̄ = sqrt(I/(A L²))
  } else {
    // I is checked through the slenderness it gives: the same blades either way.
    b.inertia = blade.number("inertia", AllowedRange::above(0, 1e300), "second moment of area in m^4");
    const double d = std::sqrt(b.inertia / (b.area * b.length * b.length));
    if (!limits::slenderness.contains(d)) {
      blade.fail_derived("inertia", fmt::format("gives d̄ = sqrt(I/(A L²)) = {:.3g}; must give d̄ in {}", d,
                                                limits::slenderness.text()));
    }
  }
}

BladeSpec read_blade(const toml::table& root, const std::string& scene_path, const std::string& source) {
  SectionReader blade(root, "blade", source);
  blade.known({"slenderness", "inertia", "area", "sections", "section", "twist_scale"});
  BladeSpec b;
  b.length = blade.number("length", limits::length_m, "span L in m");
  b.hub_radius = blade.number("hub_radius", limits::hub_radius_m, "hub radius r in m");
  const bool tabled = blade.has("sections") || blade.has("section");
  if (!tabled) read_uniform_section(blade, b);
  b.youngs_modulus = blade.number("youngs_modulus", limits::youngs_modulus_pa, "Young's modulus E in Pa");
  b.density = blade.number("density", limits::density_kg_m3, "density in kg/m^3");
  b.poisson = blade.number("poisson", limits::poisson, "Poisson's ratio");
  b.shear_coefficient = blade.number("shear_coefficient", limits::shear_coefficient, "Timoshenko shear coefficient κ");
  b.stagger_deg = blade.number("stagger_deg", limits::stagger_deg, "stagger angle β in degrees");
  if (!tabled) {
    blade.reject_unknown("a uniform blade (no blade.sections)");
    return b;
  }
  blade.mark_used("sections");
  blade.mark_used("section");
  b.sections = read_blade_sections(*root.get("blade")->as_table(), scene_path, source,
                                   {b.youngs_modulus, b.density, b.shear_coefficient});
  // docs/theory.md §9: the root station sets the scales of Λ and d̄.
  b.area = b.sections.front().area;
  b.inertia = b.sections.front().i_flap;
  b.twist_scale = blade.optional_number("twist_scale", AllowedRange::closed(-10, 10),
                                        "factor on every station's twist_deg").value_or(1);
  blade.reject_unknown("a section table (blade.sections or [[blade.section]])");
  return b;
}

ModelSpec read_model(const toml::table& root, const std::string& source) {
  SectionReader model(root, "model", source);
  ModelSpec m;
  m.basis = model.choice("basis", basis_names);
  m.terms = model.integer("terms", 1, 200);
  m.theory = model.choice("theory", theory_names);
  m.axial = model.boolean("axial");
  m.coriolis = model.boolean("coriolis");
  model.known({"reduction", "reduction_vectors", "cutoff_hz"});
  if (model.has("reduction")) {
    m.reduction.kind = model.choice("reduction", reduction_names);
  }
  if (model.has("reduction_vectors")) m.reduction.vectors = model.integer("reduction_vectors", 1, 200);
  m.reduction.cutoff_hz = model.optional_number("cutoff_hz", limits::cutoff_hz, "modal cut-off in Hz").value_or(0);
  if (m.reduction.kind != ReductionKind::modal && m.reduction.cutoff_hz > 0) {
    throw SceneKeyError(fmt::format("{}: model.cutoff_hz = {}: not used with model.reduction = \"{}\" (it needs \"modal\")",
                                    source, m.reduction.cutoff_hz, to_string(m.reduction.kind)),
                        "model.cutoff_hz", SceneKeyError::Reason::unused);
  }
  model.reject_unknown();
  return m;
}

OperationSpec read_operation(const toml::table& root, const std::string& source) {
  OperationSpec o;
  SectionReader operation(root, "operation", source);
  o.speed_rad_s = operation.number("speed_rad_s", limits::speed_rad_s, "rotor speed Ω in rad/s");
  // A static compressive tip load F_a = value · F_cr (Sinha's Fig. 9); whether the blade carries it
  // at its speed is checked where the model is assembled (model.hpp).
  o.tip_compression_over_fcr =
      operation
          .optional_number("tip_compression_over_fcr", limits::tip_compression_over_fcr,
                           "static tip compression F_a / F_cr, compression positive; F_cr = π² E I / (4 L²)")
          .value_or(0);
  operation.reject_unknown();
  return o;
}

DampingSpec read_damping(const toml::table& root, const std::string& source, double speed) {
  SectionReader damping(root, "damping", source);
  DampingSpec d;
  d.model = damping.choice("model", damping_names);
  damping.known({"ratio", "frequencies_hz"});
  if (d.damped()) {
    d.ratio = damping.number("ratio", limits::damping_ratio, "damping ratio ζ");
  }
  if (d.model == DampingModel::rayleigh) {
    d.frequencies_hz = damping.number_list("frequencies_hz", 2, limits::damping_frequency_hz, "Hz");
    if (d.frequencies_hz[0] == d.frequencies_hz[1]) {
      throw InputError(fmt::format("{}: damping.frequencies_hz = [{}, {}]: the two frequencies must differ",
                                   source, d.frequencies_hz[0], d.frequencies_hz[1]));
    }
  }
  try {
    check_damping_speed(d, speed, "operation.speed_rad_s");
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", source, e.what()));
  }
  damping.reject_unknown(fmt::format("damping.model = \"{}\"", to_string(d.model)));
  return d;
}

LoadSpec read_load(const toml::table& root, const std::string& source, double speed) {
  SectionReader load(root, "load", source);
  LoadSpec l;
  l.profile = load.choice("profile", profile_names);
  l.fmax_over_fcr = load.number("fmax_over_fcr", limits::fmax_over_fcr, "peak tip load F_max / F_cr");
  l.contact_time_rev = load.number("contact_time_rev", limits::contact_time_rev,
                                   "contact time as a fraction of a revolution");
  l.pulses_per_rev = load.integer("pulses_per_rev", 1, 1000);
  l.pulse_count = load.integer("pulse_count", 0, 1000000000);
  l.approximation = load.choice("approximation", approximation_names);
  l.mode = load.choice("mode", mode_names);
  l.friction = load.number("friction", limits::friction, "Coulomb friction coefficient μ");
  l.clearance = load.number("clearance", limits::clearance_m, "running clearance in m");
  l.pulse_frequency_hz = load.optional_number("pulse_frequency_hz", limits::pulse_frequency_hz, "pulse frequency in Hz");
  if (l.pulse_frequency_hz && speed > 0) {
    // t̄_c is a fraction of a revolution; the pulses come at their own frequency (pulse_train).
    const double contact_s = l.contact_time_rev * two_pi / speed;
    if (contact_s * *l.pulse_frequency_hz > 1 + 1e-12) {
      load.fail_both("pulse_frequency_hz", "contact_time_rev",
                     fmt::format("the contact ({:.3g} s at operation.speed_rad_s = {}) outlasts the pulse period "
                                 "({:.3g} s); lower either", contact_s, speed,
                                 1 / *l.pulse_frequency_hz));
    }
  }
  load.known({"intrusion", "contact_stiffness"});
  if (l.mode == LoadMode::clearance) {
    l.intrusion = load.number("intrusion", limits::intrusion_m,
                              "depth of the casing distortion in m; contact needs more than load.clearance");
    l.contact_stiffness = load.optional_number("contact_stiffness", limits::contact_stiffness_n_m,
                                               "penalty stiffness of the casing in N/m");
    if (l.profile == PulseProfile::impulse) {
      throw InputError(fmt::format("{}: load.profile = \"impulse\": has no shape for the casing distortion in "
                                   "load.mode = \"clearance\"; use half-sine, cosine, triangular, saw-tooth or rectangular",
                                   source));
    }
  }
  if (l.contact_time_rev * (l.pulses_per_rev) > 1 + 1e-12) {
    load.fail_both("contact_time_rev", "pulses_per_rev",
                   fmt::format("pulses overlap; t̄_c must be <= 1/pulses_per_rev = {:.6g}", 1.0 / l.pulses_per_rev));
  }
  load.reject_unknown("load.mode = \"force\"");
  return l;
}

// `source` is the scene's name as messages show it.
Scene read_scene(const toml::table& root, const std::string& source_name, const std::string& source) {
  check_sections(root, source);
  Scene scene;
  scene.source = source_name;
  scene.blade = read_blade(root, source_name, source);
  scene.model = read_model(root, source);
  scene.operation = read_operation(root, source);
  scene.damping = read_damping(root, source, scene.operation.speed_rad_s);
  scene.load = read_load(root, source, scene.operation.speed_rad_s);
  if (root.contains("requirements")) scene.requirements = read_requirements(root, source);
  return scene;
}

}  // namespace

Scene parse_scene(const std::string& toml_text, const std::string& source_name,
                  const std::vector<std::string>& overrides) {
  const std::string source = echoed(source_name, max_path_shown);
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw InputError(fmt::format("{}:{}:{}: not valid TOML: {}", source, where.line, where.column,
                                 echoed(e.description(), 200)));
  }
  for (const std::string& assignment : overrides) apply_override(root, assignment);
  return read_scene(root, source_name, source);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_scene(read_scene_file(path), path, overrides);
}

std::string read_scene_file(const std::string& path) {
  const std::string shown = echoed(path, max_path_shown);
  const auto refuse = [&shown](const std::string& why) {
    throw InputError(fmt::format("{}: cannot read the scene file: {}", shown, why));
  };
  // Only a regular file: /dev/zero would be read without end, a FIFO without a writer waits forever.
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) refuse(std::strerror(errno));
  if (S_ISDIR(info.st_mode)) refuse("it is a directory");
  if (!S_ISREG(info.st_mode)) {
    refuse(fmt::format("it is not a regular file but {}", S_ISFIFO(info.st_mode)   ? "a FIFO"
                                                          : S_ISCHR(info.st_mode) ? "a character device"
                                                          : S_ISBLK(info.st_mode) ? "a block device"
                                                          : S_ISSOCK(info.st_mode) ? "a socket"
                                                                                   : "a special file"));
  }
  if (static_cast<std::uintmax_t>(info.st_size) > max_scene_bytes) {
    refuse(fmt::format("it has {} bytes; a scene has at most {}", info.st_size, max_scene_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) refuse(std::strerror(errno));
  // At most one byte past the limit: the file may have grown since stat.
  std::string text(max_scene_bytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) refuse(std::strerror(errno));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > max_scene_bytes) refuse(fmt::format("it has more than {} bytes", max_scene_bytes));
  return text;
}

Scene scene_at(Scene scene, double speed_rad_s, double theta_rad_s, double fmax_over_fcr) {
  scene.operation.speed_rad_s = speed_rad_s;
  scene.load.pulse_frequency_hz = theta_rad_s / two_pi;
  scene.load.fmax_over_fcr = fmax_over_fcr;
  return scene;
}

void check_damping_speed(const DampingSpec& damping, double speed_rad_s, const std::string& speed_name) {
  if (damping.model == DampingModel::paper && !(speed_rad_s > 0)) {
    throw InputError(fmt::format("damping.model = \"paper\": C_D = (2ζ/Ω) K_S needs {} > 0, not {} rad/s (use "
                                 "\"modal\" or \"rayleigh\" at rest)", speed_name, speed_rad_s));
  }
}

const char* to_string(BasisKind k) { return name_of(basis_names, k); }
const char* to_string(BeamTheory t) { return name_of(theory_names, t); }
const char* to_string(DampingModel d) { return name_of(damping_names, d); }
const char* to_string(PulseProfile p) { return name_of(profile_names, p); }
const char* to_string(ReductionKind k) { return name_of(reduction_names, k); }
const char* to_string(LoadApproximation a) { return name_of(approximation_names, a); }

}  // namespace bladestab
