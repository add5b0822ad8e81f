#include "rcdem/config/scenario.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <sstream>

#include "rcdem/config/bar_path.hpp"
#include "rcdem/config/scenario_bindings.hpp"
#include "rcdem/config/scenario_checks.hpp"
#include "rcdem/config/scenario_text.hpp"
#include "rcdem/config/solver_preset.hpp"
#include "rcdem/config/specimen_geometry.hpp"
#include "rcdem/config/specimen_registry.hpp"
#include "rcdem/core/error.hpp"

namespace rcdem {

namespace {

using config::KeyDecl;
using config::KeyType;
using config::Schema;
using config::Value;

struct Reader {
  const Schema& schema;
  std::string file;
  std::map<std::string, Value> values;
  std::map<std::string, int> lines;

  std::string where(const toml::node& node) const {
    if (file.rfind("--set ", 0) == 0) return file;  // a value from the command line
    return fmt::format("{}:{}", file, node.source().begin.line);
  }

  [[noreturn]] void bad_value(const toml::node& node, const KeyDecl& decl, const std::string& got,
                              const std::string& path = "") const {
    fail("{}: key '{}': expected {}, got {}", where(node), path.empty() ? decl.path : path,
         Schema::describe_expected(decl), got);
  }

  static std::string describe_node(const toml::node& node) {
    std::ostringstream s;
    if (node.is_string())
      s << '"' << *node.value<std::string>() << '"';
    else if (node.is_table())
      s << "a table";
    else if (node.is_array())
      s << "an array";
    else if (auto f = node.value_exact<double>())
      s << fmt::format("{}", *f);  // shortest round-trip form: 0.05, not 0.050000000000000003
    else
      node.visit([&](const auto& v) {
        if constexpr (toml::is_value<decltype(v)>) s << v;
      });
    return s.str();
  }

  // Subnormal numbers (below 2.2e-308) are no physical value: out of every range.
  bool in_range(double v, const config::Range& r) const {
    if (!std::isfinite(v) || std::fpclassify(v) == FP_SUBNORMAL) return false;
    if (r.min_exclusive ? !(v > r.min) : !(v >= r.min)) return false;
    if (r.max_exclusive ? !(v < r.max) : !(v <= r.max)) return false;
    return true;
  }

  static std::string describe_number(double v) {
    return std::fpclassify(v) == FP_SUBNORMAL ? fmt::format("{} (a subnormal number)", v)
                                              : fmt::format("{}", v);
  }

  std::optional<double> number(const toml::node& node) const {
    if (auto f = node.value_exact<double>()) return *f;
    if (auto i = node.value_exact<std::int64_t>()) return static_cast<double>(*i);
    return std::nullopt;
  }

  void read_key(const toml::node& node, const KeyDecl& decl, const std::string& path) {
    Value value;
    switch (decl.type) {
      case KeyType::Real: {
        const auto v = number(node);
        if (!v) bad_value(node, decl, describe_node(node), path);
        if (!in_range(*v, decl.range)) bad_value(node, decl, describe_number(*v), path);
        value = *v;
        break;
      }
      case KeyType::Integer: {
        const auto v = node.value_exact<std::int64_t>();
        if (!v) bad_value(node, decl, describe_node(node), path);
        if (!in_range(static_cast<double>(*v), decl.range))
          bad_value(node, decl, fmt::format("{}", *v), path);
        value = *v;
        break;
      }
      case KeyType::Boolean: {
        const auto v = node.value_exact<bool>();
        if (!v) bad_value(node, decl, describe_node(node), path);
        value = *v;
        break;
      }
      case KeyType::String: {
        const auto v = node.value_exact<std::string>();
        if (!v) bad_value(node, decl, describe_node(node), path);
        if (!decl.choices.empty() &&
            std::find(decl.choices.begin(), decl.choices.end(), *v) == decl.choices.end())
          bad_value(node, decl, describe_node(node), path);
        value = *v;
        break;
      }
      case KeyType::RealArray: {
        const auto* array = node.as_array();
        if (!array) bad_value(node, decl, describe_node(node), path);
        const int size = static_cast<int>(array->size());
        const bool fits = decl.array_step > 0
                              ? size % decl.array_step == 0 && size >= 2 * decl.array_step
                              : size == decl.array_size;
        if (!fits && !(array->empty() && decl.default_value))
          bad_value(node, decl, fmt::format("an array of {} elements", array->size()), path);
        std::vector<double> v;
        for (const auto& element : *array) {
          const auto x = number(element);
          if (!x) bad_value(node, decl, describe_node(element) + " in the array", path);
          if (!in_range(*x, decl.range))
            bad_value(node, decl, describe_number(*x) + " in the array", path);
          v.push_back(*x);
        }
        value = std::move(v);
        break;
      }
      case KeyType::StringArray: {
        const auto* array = node.as_array();
        if (!array) bad_value(node, decl, describe_node(node), path);
        std::vector<std::string> v;
        for (const auto& element : *array) {
          const auto x = element.value_exact<std::string>();
          if (!x) bad_value(node, decl, describe_node(element) + " in the array", path);
          v.push_back(*x);
        }
        value = std::move(v);
        break;
      }
    }
    values[path] = std::move(value);
    lines[path] = static_cast<int>(node.source().begin.line);
  }

  void read_table(const toml::table& table, const std::string& prefix) {
    for (const auto& [raw_key, node] : table) {
      const std::string name(raw_key.str());
      const std::string path = prefix.empty() ? name : prefix + "." + name;
      const KeyDecl* decl = schema.find_key(path);
      if (node.is_table()) {
        if (decl) bad_value(node, *decl, "a table", path);
        if (!schema.is_section(path)) unknown(node, path, prefix);
        for (const auto& sec : schema.sections())
          if (sec.path.find('*') != std::string::npos && config::path_matches(sec.path, path)) {
            instances[sec.path].push_back(path);
            lines[path] = static_cast<int>(node.source().begin.line);
          }
        read_table(*node.as_table(), path);
        continue;
      }
      if (schema.is_section(path))
        fail("{}: '{}' is a section: expected a table [{}], got {}", where(node), path, path,
             node.is_array() ? "an array" : describe_node(node));
      if (!decl) unknown(node, path, prefix);
      read_key(node, *decl, path);
    }
  }

  [[noreturn]] void unknown(const toml::node& node, const std::string& path,
                            const std::string& section) const {
    std::string known;
    for (const auto& n : schema.keys_in_section(section)) known += (known.empty() ? "" : ", ") + n;
    fail("{}: unknown key '{}' (known in [{}]: {})", where(node), path,
         section.empty() ? "top level" : section, known);
  }

  // Names given to '*' sections, e.g. "plates.top" for the pattern "plates.*".
  std::map<std::string, std::vector<std::string>> instances;

  void fill_defaults() {
    for (const auto& key : config::fill_solver_preset(values))
      if (!origin.count(key))
        origin[key] = fmt::format("{} (solver.preset \"{}\")", file,
                                  std::get<std::string>(values.at(config::kSolverPresetKey)));
    for (const auto& decl : schema.keys()) {
      const auto star = decl.path.find('*');
      if (star != std::string::npos) {
        // Keys of a named section get their defaults, or are required, in each instance given.
        const std::string pattern = decl.path.substr(0, decl.path.rfind('.'));
        for (const auto& inst : instances[pattern]) {
          const std::string path = inst + decl.path.substr(decl.path.rfind('.'));
          if (values.count(path)) continue;
          if (!decl.default_value)
            fail("{}: missing required key '{}' ({}): expected {}", file, path, decl.doc,
                 Schema::describe_expected(decl));
          values[path] = *decl.default_value;
        }
        continue;
      }
      if (values.count(decl.path)) continue;
      if (!decl.default_value) {
        std::string doc = decl.doc;
        if (!doc.empty() && doc.back() == '.') doc.pop_back();
        fail("{}: missing required key '{}' ({}): expected {}", file, decl.path, doc,
             Schema::describe_expected(decl));
      }
      values[decl.path] = *decl.default_value;
    }
  }

  const std::string& string(const std::string& p) const {
    return std::get<std::string>(values.at(p));
  }
  // Keys set from the command line (--set): where messages say they come from.
  std::map<std::string, std::string> origin;

  std::string at(const std::string& p) const {
    if (const auto o = origin.find(p); o != origin.end()) return o->second;
    const auto it = lines.find(p);
    return it == lines.end() ? file + " (default value)" : fmt::format("{}:{}", file, it->second);
  }
};

// The bilinear law's softening branch must be less steep than its elastic branch (no snap-back,
// paper (S2)-(S3)): u_ult = 2 G_f / strength above u_0 = strength d / (E_bar [alpha]) for the
// longest contacts, whose centres lie about one largest diameter d apart.
void check_softening_is_stable(const Reader& r, const Scenario& s) {
  if (s.law != "BL") return;
  const auto& c = s.contact;
  const Real d = std::max(s.generation.aggregate_d_max, s.generation.mortar_d_max);
  const Real need_n = c.sigma_nt * c.sigma_nt * d / (2.0 * c.E_bar);
  const Real need_s = c.tau * c.tau * d / (2.0 * c.alpha * c.E_bar);
  const bool normal = c.G_fn < need_n;
  if (!normal && !(c.G_fs < need_s)) return;
  const char* key = normal ? "contact.G_fn" : "contact.G_fs";
  fail(
      "{}: key '{}' = {} J/m^2 is too small for the bilinear law: its softening branch would be "
      "steeper than the elastic one (snap-back) at contacts {} m long; expected at least {:.4g} "
      "J/m^2 ({} d / (2 E_bar{}))",
      r.at(key), key, normal ? c.G_fn : c.G_fs, d, normal ? need_n : need_s,
      normal ? "sigma_nt^2" : "tau^2", normal ? "" : " alpha");
}

// Names of plates and bars become history.csv's column names and file names: short, and
// letters, digits, '_' and '-' only.
void check_section_names(const Reader& r) {
  for (const std::string pattern : {"plates.*", "bars.*", "gauges.*"}) {
    const auto it = r.instances.find(pattern);
    if (it == r.instances.end()) continue;
    for (const auto& inst : it->second) {
      const std::string name = inst.substr(inst.find('.') + 1);
      const bool ok = !name.empty() && name.size() <= 64 &&
                      std::all_of(name.begin(), name.end(), [](char ch) {
                        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' ||
                               ch == '-';
                      });
      if (!ok)
        fail("{}: section [{}{}]: expected a name of 1 to 64 letters, digits, '_' or '-'",
             r.at(inst), pattern.substr(0, pattern.size() - 1),
             name.size() > 40 ? name.substr(0, 40) + "..." : name);
    }
  }
}

void check_consistency(const Reader& r, const Scenario& s) {
  const auto& g = s.generation;
  if (g.aggregate_d_min > g.aggregate_d_max)
    fail(
        "{}: key 'generation.aggregate.d_min' ({} m) must not exceed "
        "'generation.aggregate.d_max' ({} m)",
        r.at("generation.aggregate.d_min"), g.aggregate_d_min, g.aggregate_d_max);
  if (g.mortar_d_min > g.mortar_d_max)
    fail(
        "{}: key 'generation.mortar.d_min' ({} m) must not exceed 'generation.mortar.d_max' ({} m)",
        r.at("generation.mortar.d_min"), g.mortar_d_min, g.mortar_d_max);
  const Real largest = std::max(g.aggregate_d_max, g.mortar_d_max);
  const Real smallest_side = s.specimen.size.minCoeff();
  if (smallest_side < 2.0 * largest)
    fail(
        "{}: key 'specimen.size': the smallest side ({} m) must be at least two of the largest "
        "particle diameters ({} m)",
        r.at("specimen.size"), smallest_side, 2.0 * largest);
  if (s.specimen.shape != "beam" && s.specimen.notch_depth > 0.0)
    fail("{}: key 'specimen.notch_depth': a notch needs specimen.shape = \"beam\"",
         r.at("specimen.notch_depth"));
  if (s.specimen.notch_depth > 0.0 && s.specimen.notch_depth >= s.specimen.size.z() - 2.0 * largest)
    fail(
        "{}: key 'specimen.notch_depth' ({} m) must leave at least two particle diameters of the "
        "depth ({} m)",
        r.at("specimen.notch_depth"), s.specimen.notch_depth, s.specimen.size.z());
  check_softening_is_stable(r, s);
  const SpecimenGeometry geometry = specimen_geometry(s);
  const Real volume = geometry.volume();
  const Real smallest = kPi / 6.0 * std::pow(std::min(g.aggregate_d_min, g.mortar_d_min), 3);
  const Real solid = (1.0 - g.porosity) * volume;
  if (solid < smallest)
    fail(
        "{}: key 'generation.porosity' ({}) leaves a solid volume of {:.3g} m^3, less than one "
        "particle: the specimen would hold no particle",
        r.at("generation.porosity"), g.porosity, solid);
  // The generator fills volumes to within one sphere, so a content is feasible only if it stays
  // one largest aggregate below the solid volume (1 - porosity) V.
  const Real aggregate_fraction = g.aggregate_content / g.aggregate_density;
  const Real one_aggregate = kPi / 6.0 * std::pow(g.aggregate_d_max, 3) / volume;
  if (aggregate_fraction > 0.0 && aggregate_fraction + one_aggregate >= 1.0 - g.porosity)
    fail(
        "{}: key 'generation.aggregate.content': {} kg/m^3 at density {} kg/m^3 fills {:.3f} of "
        "the volume, which cannot fit below the solid fraction 1 - porosity = {:.3f}",
        r.at("generation.aggregate.content"), g.aggregate_content, g.aggregate_density,
        aggregate_fraction, 1.0 - g.porosity);
}

// Every bound key's member from the value read (config/scenario_bindings.hpp); `prefix`: the
// named section ("plates.top") of an instance's keys.
template <class Target>
void set_bound(const Reader& r, const std::vector<config::BoundKey<Target>>& keys,
               const std::string& prefix, Target& t) {
  for (const auto& k : keys) k.set(r.values.at(prefix.empty() ? k.path : prefix + "." + k.path), t);
}

void check_solver(const Reader& r, const Scenario& s) {
  // SPEC 6: safety <= 0.5 on the per-body estimate, <= 0.8 on the assembly's critical step.
  if (s.solver.dt_safety > max_dt_safety(s.solver.estimate))
    fail(
        "{}: key 'solver.dt_safety' = {}: with solver.time_step_estimate = \"per_body\" it must "
        "be at most 0.5 (SPEC 6); up to 0.8 needs time_step_estimate = \"assembled\"",
        r.at("solver.dt_safety"), s.solver.dt_safety);
  if (s.solver.time_step > 0.0 && s.solver.time_step < kMinimumTimeStep)
    fail("{}: key 'solver.time_step' = {} s: expected 0 (automatic) or at least {} s",
         r.at("solver.time_step"), s.solver.time_step, kMinimumTimeStep);
}

// The segments of the program of `owner` ("plates.top"), in the file's order, each checked for
// the keys its kind needs; cycles stay one segment (the solver expands them).
std::vector<SegmentSettings> convert_program(const Reader& r, const std::string& owner) {
  std::vector<SegmentSettings> program;
  const std::string pattern = owner.substr(0, owner.find('.')) + ".*.program.*";
  const auto it = r.instances.find(pattern);
  if (it == r.instances.end()) return program;
  for (const auto& inst : it->second) {
    if (inst.rfind(owner + ".program.", 0) != 0) continue;
    SegmentSettings g;
    g.name = inst.substr(inst.rfind('.') + 1);
    set_bound(r, config::scenario_bindings().segment, inst, g);
    const auto need = [&](bool ok, const char* key, const char* what) {
      if (!ok)
        fail("{}: section [{}]: a '{}' segment needs {}: key '{}.{}'", r.at(inst), inst,
             r.string(inst + ".kind"), what, inst, key);
    };
    switch (g.kind) {
      case SegmentKind::Velocity:
        need(g.velocity != 0.0 || g.duration > 0.0, "velocity", "a velocity or a duration");
        break;
      case SegmentKind::Hold:
        need(g.duration > 0.0, "duration", "a duration > 0");
        break;
      case SegmentKind::Displacement:
      case SegmentKind::Load:
        need(g.speed > 0.0, "speed", "a speed > 0");
        need(r.lines.count(inst + ".target") > 0, "target", "a target");
        break;
      case SegmentKind::Force:
        need(g.speed > 0.0, "speed", "a largest speed > 0");
        need(g.response_time > 0.0, "response_time", "a response time > 0");
        need(g.duration > 0.0, "duration", "a duration > 0");
        need(r.lines.count(inst + ".target") > 0, "target", "a target load");
        break;
      case SegmentKind::Cycles:
        need(g.speed > 0.0, "speed", "a speed > 0");
        need(g.amplitude != 0.0, "amplitude", "an amplitude other than 0");
        break;
    }
    program.push_back(g);
  }
  return program;
}

// One [plates.NAME] section; `s` gives the specimen's size its extent is checked against.
PlateSettings convert_plate(const Reader& r, const Scenario& s, const std::string& inst) {
  PlateSettings p;
  p.name = inst.substr(inst.find('.') + 1);
  set_bound(r, config::scenario_bindings().plate, inst, p);
  const std::string face = r.string(inst + ".face");
  p.axis = face[0] - 'x';
  p.side = face[1] == '-' ? -1 : 1;
  p.program = convert_program(r, inst);
  if (!p.program.empty() && p.velocity != 0.0)
    fail("{}: key '{}.velocity': a plate with a program moves by its program; expected no "
         "velocity",
         r.at(inst + ".velocity"), inst);
  if (!p.extent.empty() && (p.extent[0] >= p.extent[1] || p.extent[2] >= p.extent[3]))
    fail(
        "{}: key '{}.extent': expected [u_min, u_max, v_min, v_max] with u_min < u_max and "
        "v_min < v_max",
        r.at(inst + ".extent"), inst);
  if (!p.extent.empty()) {
    const auto [u, v] = face_axes(p.axis);
    if (p.extent[1] <= 0.0 || p.extent[0] >= s.specimen.size[u] || p.extent[3] <= 0.0 ||
        p.extent[2] >= s.specimen.size[v])
      fail(
          "{}: key '{}.extent': the rectangle [{}, {}] x [{}, {}] m misses the specimen's "
          "face [0, {}] x [0, {}] m",
          r.at(inst + ".extent"), inst, p.extent[0], p.extent[1], p.extent[2], p.extent[3],
          s.specimen.size[u], s.specimen.size[v]);
  }
  return p;
}

// The bar's length, and its axis inside the specimen with a cover of one radius across it (along
// it, a straight bar's end may reach a face: a pull-out bar leaves the specimen there).
void check_bar_axis(const Reader& r, const Scenario& s, const std::string& inst,
                    const BarSettings& b) {
  const Real length = b.bent() ? b.length() : (b.end - b.start).norm();
  const std::string key = inst + (b.bent() ? ".path" : ".end");
  if (length < 2.0 * b.diameter)
    fail("{}: bar '{}' is {} m long: expected at least two diameters ({} m) between start and end",
         r.at(key), b.name, length, 2.0 * b.diameter);
  const Vec3 dir = b.bent() ? Vec3(Vec3::Zero()) : Vec3((b.end - b.start) / length);
  const std::vector<Vec3> axis = b.centreline();
  for (std::size_t k = 0; k < axis.size(); ++k) {
    const Vec3& p = axis[k];
    for (int ax = 0; ax < 3; ++ax) {
      const Real cover = std::abs(dir[ax]) > 0.999 ? 0.0 : 0.5 * b.diameter;
      if (p[ax] < cover || p[ax] > s.specimen.size[ax] - cover)
        fail(
            "{}: bar '{}': its {} ({}, {}, {}) m is not inside the specimen with half a "
            "diameter of cover",
            r.at(b.bent() ? key : inst + (k == 0 ? ".start" : ".end")), b.name,
            b.bent() ? "axis at" : k == 0 ? "start" : "end", p[0], p[1], p[2]);
    }
  }
}

// One [bars.NAME] section, checked against the specimen in `s`.
BarSettings convert_bar(const Reader& r, const Scenario& s, const std::string& inst) {
  BarSettings b;
  b.name = inst.substr(inst.find('.') + 1);
  set_bound(r, config::scenario_bindings().bar, inst, b);
  b.program = convert_program(r, inst);
  if (!b.program.empty() && b.pull_velocity != 0.0)
    fail("{}: key '{}.pull_velocity': a bar with a program is pulled by its program; expected "
         "no pull_velocity",
         r.at(inst + ".pull_velocity"), inst);
  if (b.interface == InterfaceLaw::EL && b.interface_softening != BarSettings{}.interface_softening)
    fail(
        "{}: key '{}.interface_softening': expected only with a nonlinear interface (NL-A, "
        "NL-B); interface = \"EL\" does not soften",
        r.at(inst + ".interface_softening"), inst);
  if (b.interface == InterfaceLaw::EL &&
      (b.interface_strength_scale != 1.0 || b.interface_energy_scale != 1.0)) {
    const std::string key = inst + (b.interface_strength_scale != 1.0 ? ".interface_strength_scale"
                                                                      : ".interface_energy_scale");
    fail(
        "{}: key '{}': expected only with a nonlinear interface (NL-A, NL-B); interface = \"EL\" "
        "has no strength to scale",
        r.at(key), key);
  }
  if (!b.bent() && !(r.lines.count(inst + ".start") && r.lines.count(inst + ".end")))
    fail("{}: section [{}]: a bar needs its axis: keys '{}.start' and '{}.end', or '{}.path'",
         r.at(inst), inst, inst, inst, inst);
  if (b.bent() && (r.lines.count(inst + ".start") || r.lines.count(inst + ".end")))
    fail("{}: section [{}]: a bar is straight (start, end) or bent (path), not both", r.at(inst),
         inst);
  if (!b.bent() && (b.closed || b.bend_radius > 0.0))
    fail("{}: section [{}]: closed and bend_radius are for a bent bar (a path)", r.at(inst),
         inst);
  if (b.bent()) {
    std::vector<Vec3> corners;
    for (std::size_t i = 0; i + 2 < b.path.size(); i += 3)
      corners.emplace_back(b.path[i], b.path[i + 1], b.path[i + 2]);
    const Real radius = b.bend_radius > 0.0 ? b.bend_radius : 2.0 * b.diameter;
    b.axis = bar_centreline(corners, b.closed, radius,
                            fmt::format("{}: key '{}.path'", r.at(inst + ".path"), inst));
    b.start = b.axis.front();
    b.end = b.closed ? b.axis[1] : b.axis.back();
  }
  check_bar_axis(r, s, inst, b);
  return b;
}

bool has_plate(const Scenario& s, const std::string& name) {
  return std::any_of(s.plates.begin(), s.plates.end(),
                     [&](const PlateSettings& p) { return p.name == name; });
}

// One [gauges.NAME] section, its plates checked against the scenario's.
GaugeSettings convert_gauge(const Reader& r, const Scenario& s, const std::string& inst) {
  GaugeSettings g;
  g.name = inst.substr(inst.find('.') + 1);
  set_bound(r, config::scenario_bindings().gauge, inst, g);
  const bool opening = g.kind == GaugeKind::Opening;
  if (opening && !r.lines.count(inst + ".to"))
    fail("{}: section [{}]: an opening gauge needs its second point: key '{}.to'", r.at(inst),
         inst, inst);
  if (opening && (g.to - g.point).norm() <= 0.0)
    fail("{}: key '{}.to': expected a point other than '{}.point'", r.at(inst + ".to"), inst,
         inst);
  if (!opening && g.direction() == GaugeSettings::kAlong)
    fail("{}: key '{}.direction': 'along' is for opening gauges; expected 'x', 'y' or 'z'",
         r.at(inst + ".direction"), inst);
  if (opening && !g.relative_to.empty())
    fail("{}: key '{}.relative_to': expected only on a displacement gauge", r.at(inst), inst);
  for (const Vec3* p : {&g.point, opening ? &g.to : &g.point})
    for (int ax = 0; ax < 3; ++ax)
      if ((*p)[ax] < 0.0 || (*p)[ax] > s.specimen.size[ax])
        fail("{}: gauge '{}': the point ({}, {}, {}) m is outside the specimen", r.at(inst),
             g.name, (*p)[0], (*p)[1], (*p)[2]);
  for (const auto& name : g.relative_to) {
    const auto it = std::find_if(s.plates.begin(), s.plates.end(),
                                 [&](const PlateSettings& p) { return p.name == name; });
    if (it == s.plates.end())
      fail("{}: key '{}.relative_to': no plate named '{}'", r.at(inst + ".relative_to"), inst,
           name);
    if (it->axis != g.direction())
      fail("{}: key '{}.relative_to': plate '{}' moves along {}, the gauge measures along {}",
           r.at(inst + ".relative_to"), inst, name, "xyz"[it->axis], "xyz"[g.direction()]);
  }
  return g;
}

// The plates that make the load exist, once each, and the displacement gauge.
void check_load_plates(const Reader& r, const Scenario& s) {
  if (!s.control_plates.empty() && !s.control_plate.empty())
    fail("{}: set loading.control_plate or loading.control_plates, not both",
         r.at("loading.control_plates"));
  for (std::size_t i = 0; i < s.control_plates.size(); ++i) {
    const std::string& name = s.control_plates[i];
    if (!has_plate(s, name))
      fail("{}: key 'loading.control_plates': no plate named '{}' (add a [plates.{}] section)",
           r.at("loading.control_plates"), name, name);
    if (std::find(s.control_plates.begin(), s.control_plates.begin() + static_cast<long>(i),
                  name) != s.control_plates.begin() + static_cast<long>(i))
      fail("{}: key 'loading.control_plates': plate '{}' is named twice",
           r.at("loading.control_plates"), name);
  }
  if (!s.displacement_gauge.empty() &&
      std::none_of(s.gauges.begin(), s.gauges.end(),
                   [&](const GaugeSettings& g) { return g.name == s.displacement_gauge; }))
    fail("{}: key 'loading.displacement_gauge': no gauge named '{}' (add a [gauges.{}] section)",
         r.at("loading.displacement_gauge"), s.displacement_gauge, s.displacement_gauge);
}

// The control named exists: a pulled bar, or a plate, not both.
void check_control(const Reader& r, const Scenario& s) {
  check_load_plates(r, s);
  if (!s.control_bar.empty()) {
    const auto it = std::find_if(s.bars.begin(), s.bars.end(),
                                 [&](const BarSettings& b) { return b.name == s.control_bar; });
    if (it == s.bars.end() || !it->pulled())
      fail(
          "{}: key 'loading.control_bar': expected the name of a bar with pull_velocity > 0 or "
          "a program, "
          "got '{}'",
          r.at("loading.control_bar"), s.control_bar);
    if (!s.load_plates().empty())
      fail("{}: set loading.control_plate(s) or loading.control_bar, not both",
           r.at("loading.control_bar"));
  }
  if (!s.control_plate.empty() && !has_plate(s, s.control_plate))
    fail("{}: key 'loading.control_plate': no plate named '{}' (add a [plates.{}] section)",
         r.at("loading.control_plate"), s.control_plate, s.control_plate);
}

Scenario convert(Reader& r, const std::string& text) {
  // toml++ walks keys in sorted order: put the named sections back in the order of the file.
  for (auto& [pattern, names] : r.instances)
    std::stable_sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) {
      return r.lines.at(a) < r.lines.at(b);
    });
  Scenario s;
  s.source = r.file;
  s.text = text;
  check_section_names(r);
  set_bound(r, config::scenario_bindings().scenario, "", s);
  check_solver(r, s);
  for (const auto& inst : r.instances["plates.*"]) s.plates.push_back(convert_plate(r, s, inst));
  for (const auto& inst : r.instances["bars.*"]) s.bars.push_back(convert_bar(r, s, inst));
  for (const auto& inst : r.instances["gauges.*"]) s.gauges.push_back(convert_gauge(r, s, inst));
  check_control(r, s);
  s.key_line = r.lines;
  check_consistency(r, s);
  config::check_model_size(s);
  config::check_bar_layout(s);
  config::check_plate_layout(s);
  validate_specimen(s);
  return s;
}

// include = ["fragment.toml", ...]: each fragment's keys are read first (paths relative to this
// file), then this file's, whose values override the fragments' (e.g. a calibrated [contact]
// fragment with one value changed for a study).
void read_includes(toml::table& table, const std::string& source_name, Reader& reader) {
  const toml::node* inc = table.get("include");
  if (!inc) return;
  const std::string at = fmt::format("{}:{}: key 'include'", source_name, inc->source().begin.line);
  std::vector<std::string> files;
  if (auto one = inc->value_exact<std::string>())
    files.push_back(*one);
  else if (const auto* arr = inc->as_array())
    for (const auto& e : *arr) {
      auto f = e.value_exact<std::string>();
      if (!f) fail("{}: expected file names", at);
      files.push_back(*f);
    }
  else
    fail("{}: expected a file name or an array of them", at);
  const auto dir = std::filesystem::path(source_name).parent_path();
  for (const auto& f : files) {
    if (f.empty()) fail("{}: an empty file name", at);
    const auto path = std::filesystem::path(f).is_absolute() ? std::filesystem::path(f) : dir / f;
    const toml::table sub =
        config::parse_scenario_toml(config::read_scenario_file(path, "include", at), path.string());
    if (sub.contains("include")) fail("{}: an included file may not include others", path.string());
    reader.file = path.string();
    reader.read_table(sub, "");
  }
  reader.file = source_name;
  table.erase("include");
}

}  // namespace

Scenario parse_scenario(const std::string& text, const std::string& source_name,
                        const std::vector<config::Override>& overrides) {
  toml::table table = config::parse_scenario_toml(text, source_name);
  Reader reader{config::scenario_schema(), source_name, {}, {}, {}, {}};
  read_includes(table, source_name, reader);
  reader.read_table(table, "");
  for (const auto& o : overrides) reader.origin[o.key] = "--set '" + o.given + "'";
  reader.fill_defaults();
  Scenario s = convert(reader, text);
  for (const auto& o : overrides) s.overrides.push_back(o.given);
  return s;
}

namespace config {

void check_override(const Override& o) {
  toml::table table;
  try {
    table = toml::parse(o.key + " = " + o.value, std::string_view{"--set"});
  } catch (const toml::parse_error& e) {
    fail("--set '{}': not a key and a value ({})", o.given, e.description());
  }
  Reader reader{scenario_schema(), "--set '" + o.given + "'", {}, {}, {}, {}};
  reader.read_table(table, "");
}

}  // namespace config

Scenario load_scenario(const std::filesystem::path& path) {
  Scenario s = parse_scenario(config::read_scenario_file(path, "scenario"), path.string());
  s.source = path;
  return s;
}

}  // namespace rcdem
