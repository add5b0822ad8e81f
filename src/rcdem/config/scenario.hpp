#pragma once
// A scenario file, validated against the declared schema and turned into typed settings. A member
// initialiser below is its key's default: config/scenario_schema.cpp binds each key to its member
// and takes the default from here (config/scenario_bindings.hpp).
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "rcdem/config/schema.hpp"
#include "rcdem/core/types.hpp"

namespace rcdem {

struct SpecimenSettings {
  std::string shape;  // a name in the specimen registry
  Vec3 size = Vec3::Zero();
  Real notch_depth = 0.0;
  Real notch_width = 0.003;
};

enum class Grading { Uniform, Fuller };

struct GenerationSettings {
  std::uint64_t seed = 1;
  Real porosity = 0.10;
  int relaxation_iterations = 300;
  Real min_distance_factor = 0.5;
  std::int64_t max_particles = 5'000'000;
  Real aggregate_content = 568.5;  // kg/m^3
  Real aggregate_density = 2700.0;
  Real aggregate_d_min = 0.008, aggregate_d_max = 0.012;
  Grading aggregate_grading = Grading::Uniform;
  Real fuller_exponent = 0.5;
  Real mortar_d_min = 0.008, mortar_d_max = 0.009;
};

enum class TessellationKind { Voronoi, Radical };

// Paper Table 2, in SI units.
struct ContactParameters {
  Real E_bar = 48.7e9;
  Real alpha = 0.3;
  Real mu_c = 0.5;
  Real sigma_nt = 4.15e6;
  Real tau = 21.0e6;
  Real G_fn = 9.002;
  Real G_fs = 2380.785;
};

// How SPEC 6's time step is estimated: each body alone (solver/body_stiffness.hpp) or the
// assembled system's highest frequency (solver/critical_time_step.hpp).
enum class TimeStepEstimate { PerBody, Assembled };

// SPEC 6's largest safety factor on each estimate: 0.5 per body, 0.8 on the assembly's step.
inline Real max_dt_safety(TimeStepEstimate e) {
  return e == TimeStepEstimate::Assembled ? 0.8 : 0.5;
}

// The shortest time step rcdem takes (issue 28): a step below it means a stiffness or mass far
// outside any material, and a run would need 1e12 steps per second of loading.
inline constexpr Real kMinimumTimeStep = 1e-12;  // s

struct SolverSettings {
  Real density = 2400.0;  // kg/m^3 (material.density)
  TimeStepEstimate estimate = TimeStepEstimate::PerBody;
  Real dt_safety = 0.3;
  Real time_step = 0.0;  // 0 = automatic
  Real damping = 0.7;
  Real mass_scaling = 1.0;
  Real added_mass_limit = 0.0;  // selective mass scaling (solver/selective_mass_scaling.hpp)
  Real bar_rotational_inertia_scaling = 1.0;       // the cylinders' moments of inertia only
  Real particle_rotational_inertia_scaling = 1.0;  // the particles' moments of inertia only
  bool condense_elastic_contacts = true;           // contact/elastic_condensation.hpp
  bool hold_unloading_contacts = true;             // contact/held_contacts.hpp
  bool hold_softening_contacts = true;             // ... softening ones too
  bool hold_intact_contacts = true;                // ... intact ones near their limits too
};

// loading.adaptive_rate and its bounds (solver/loading_rate.hpp).
struct LoadingRateSettings {
  bool adaptive = false;
  Real max_factor = 4.0;
  Real kinetic_ratio = 0.01;
  Real damage_work_ratio = 0.5;
  Real doubling_time = 2e-3;  // s
};

// The two axes spanning a plate on a face normal to `axis`, in x, y, z order.
inline std::pair<int, int> face_axes(int axis) { return {axis == 0 ? 1 : 0, axis == 2 ? 1 : 2}; }

// One segment of a loading program (issue 41, item 2; docs/model.md 13), a [plates.P.program.NAME]
// or [bars.B.program.NAME] section, run in the file's order. Velocities and displacements are
// along the plate's axis (a pulled bar: along its pull), loads in the plate's or bar's load sign.
enum class SegmentKind { Velocity, Displacement, Load, Hold, Force, Cycles };
struct SegmentSettings {
  std::string name;
  SegmentKind kind = SegmentKind::Velocity;
  Real velocity = 0.0;   // velocity: m/s
  Real duration = 0.0;   // velocity (0: until the run stops), hold, force: s
  Real target = 0.0;     // displacement: m; load, force: N
  Real speed = 0.0;      // displacement, load, cycles: m/s; force: the servo's largest speed
  std::int64_t count = 1;                      // cycles
  Real amplitude = 0.0, amplitude_step = 0.0;  // cycles: the first peak displacement, its growth
  Real unload_to = 0.0;                        // cycles: the load each cycle unloads to, N
  Real response_time = 0.0;                    // force: the servo's time constant, s
  Real tolerance = 0.01;  // force: the hold's duration counts from the load within this of target
  Real stiffness = 0.0;  // force: N/m the servo assumes; 0: the secant at the segment's start
};

struct PlateSettings {
  std::string name;
  int axis = 2;              // 0, 1, 2 for x, y, z
  int side = -1;             // -1: the face at the low end of the axis, +1: the high end
  std::vector<Real> extent;  // [u_min, u_max, v_min, v_max] or empty for the whole face
  Real velocity = 0.0;
  Real ramp_time = 0.0;
  bool glued = false;
  Real friction = 0.0;
  std::vector<SegmentSettings> program;  // empty: `velocity` after the ramp
  // [u_min, u_max, v_min, v_max] in face_axes(axis): the extent, or the whole face of a specimen
  // of `size` (its origin at a corner).
  std::vector<Real> rectangle(const Vec3& size) const {
    const auto [u, v] = face_axes(axis);
    return extent.empty() ? std::vector<Real>{0.0, size[u], 0.0, size[v]} : extent;
  }
};

enum class InterfaceLaw { EL, NL_A, NL_B };

struct BarSettings {
  std::string name;
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();
  Real diameter = 0.0;
  Real cylinder_length = 0.032;
  Real E = 200.0e9, nu = 0.3, f_y = 0.0, density = 7850.0;
  InterfaceLaw interface = InterfaceLaw::NL_B;
  // The softening law of an NL-A or NL-B interface, by its name in contact/laws/law_registry.hpp.
  std::string interface_softening = "BL";
  Real interface_strength_scale = 1.0;  // on sigma_n,t and tau of a BL interface
  Real interface_energy_scale = 1.0;    // on G_fn and G_fs of a BL interface
  Real sphere_spacing = 0.0;            // 0 = D / 2
  Real pull_velocity = 0.0;             // pull-out of the first cylinder along end -> start
  Real pull_ramp_time = 0.0;
  std::vector<SegmentSettings> program;  // a pull-out program instead of pull_velocity
  // A bent bar (issue 41, item 4): its corner points x0, y0, z0, x1, ... instead of start and
  // end, `closed` for a loop (a stirrup), each corner rounded with `bend_radius` (0: 2 D).
  std::vector<Real> path;
  bool closed = false;
  Real bend_radius = 0.0;
  // A bent bar's centreline, the path with its bends as chords (config/bar_path.hpp; set by the
  // loader; start is its first point).
  std::vector<Vec3> axis;
  bool pulled() const { return pull_velocity > 0.0 || !program.empty(); }
  bool bent() const { return !path.empty(); }
  // The axis as points: start and end, or a bent bar's centreline.
  std::vector<Vec3> centreline() const { return bent() ? axis : std::vector<Vec3>{start, end}; }
  // Its chords [a, b] in order, a loop's closing chord last.
  std::vector<std::pair<Vec3, Vec3>> chords() const {
    const std::vector<Vec3> p = centreline();
    std::vector<std::pair<Vec3, Vec3>> c;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) c.emplace_back(p[i], p[i + 1]);
    if (closed && p.size() > 2) c.emplace_back(p.back(), p.front());
    return c;
  }
  Real length() const {
    Real l = 0.0;
    for (const auto& [a, b] : chords()) l += (b - a).norm();
    return l;
  }
  Real spacing() const { return sphere_spacing > 0.0 ? sphere_spacing : 0.5 * diameter; }
};

// A gauge (issue 41): a measured displacement, a history.csv column `gauge_NAME_m`.
//   displacement: the material's displacement at `point` along `axis`, less the mean displacement
//                 of the `relative_to` plates (a deflection relative to the supports);
//   opening:      the material at `to` against the material at `point`, along `axis` or along the
//                 line from `point` to `to` (a crack-mouth opening).
// The material at a point: the affine displacement field fitted to the concrete particles whose
// centres lie within `radius` of it at t = 0, evaluated at the point (solver/test_measures.hpp);
// with radius 0 the nearest particle, carrying the point rigidly.
enum class GaugeKind { Displacement, Opening };
struct GaugeSettings {
  static constexpr int kAuto = -1;   // displacement: z; opening: along the line
  static constexpr int kAlong = 3;   // along the line from point to `to`
  std::string name;
  GaugeKind kind = GaugeKind::Displacement;
  Vec3 point = Vec3::Zero(), to = Vec3::Zero();
  int axis = kAuto;  // 0, 1, 2, kAlong or kAuto
  std::vector<std::string> relative_to;
  Real radius = 0.0;
  // The axis index or kAlong, with kAuto resolved.
  int direction() const {
    return axis != kAuto ? axis : kind == GaugeKind::Displacement ? 2 : kAlong;
  }
};

struct StopSettings {
  Real displacement = 0.0;
  Real load_drop = 0.0;
  Real post_peak_displacement = 0.0;
  Real time = 0.0;
  std::int64_t steps = 0;
  bool any() const {
    return displacement > 0 || load_drop > 0 || post_peak_displacement > 0 || time > 0 || steps > 0;
  }
};

struct OutputSettings {
  bool binary_vtu = true;
  bool write_facets = true;
  std::int64_t history_rows = 2000;
  std::int64_t snapshots = 10;
};

struct Scenario {
  std::filesystem::path source;  // the file it came from ("" for text)
  SpecimenSettings specimen;
  GenerationSettings generation;
  TessellationKind tessellation = TessellationKind::Voronoi;
  ContactParameters contact;
  std::string law = "BL";  // contact.law: a name in contact/laws/law_registry.hpp
  SolverSettings solver;
  std::vector<PlateSettings> plates;  // in the order given
  std::vector<BarSettings> bars;      // in the order given
  std::string control_plate;
  std::vector<std::string> control_plates;  // or several: the load is their reactions' sum
  std::string control_bar;  // a pulled bar, instead of a control plate
  std::vector<GaugeSettings> gauges;  // in the order given
  std::string displacement_gauge;     // the test's displacement, instead of the control's
  LoadingRateSettings loading_rate;
  StopSettings stop;
  OutputSettings output;
  std::vector<std::string> overrides;   // --set KEY=VALUE items applied to `text`
  std::string text;                     // the scenario as given, kept for the run directory
  std::map<std::string, int> key_line;  // where each key was set, for later error messages

  // The plates whose reactions sum to the load: control_plates, or control_plate alone.
  std::vector<std::string> load_plates() const {
    if (!control_plates.empty()) return control_plates;
    if (!control_plate.empty()) return {control_plate};
    return {};
  }
  // The control's name as reports give it: the plates joined by '+', or the pulled bar.
  std::string control_name() const {
    std::string name;
    for (const auto& p : load_plates()) (name += name.empty() ? "" : "+") += p;
    return name.empty() ? control_bar : name;
  }
};

// Reads, validates (types, ranges, unknown keys, cross-key consistency) and converts a scenario.
// Throws rcdem::Error with "file:line: ..." on any problem.
Scenario load_scenario(const std::filesystem::path& path);
namespace config {

// One `--set KEY=VALUE` (config/scenario_overrides.hpp): VALUE is a TOML value (0.3, "beam",
// [0.1, 0.1, 0.1], true), or a bare word taken as a string (beam).
struct Override {
  std::string key;
  std::string value;  // as TOML text
  std::string given;  // KEY=VALUE as on the command line, for messages
};

// Checks one override's key and value against the schema as if written in a file; errors name
// "--set 'KEY=VALUE'".
void check_override(const Override& o);

}  // namespace config

// `overrides`: the --set items already written into `text`; errors about their keys name them.
Scenario parse_scenario(const std::string& text, const std::string& source_name,
                        const std::vector<config::Override>& overrides = {});

}  // namespace rcdem
