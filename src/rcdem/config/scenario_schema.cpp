// The declaration of every scenario key, bound to the member it sets where it sets one member:
// one place for the key, its type, range, unit and doc, its default (the member's initial value)
// and its conversion (config/scenario_bindings.hpp). Read by the loader, print-schema and the docs.
#include <limits>
#include <type_traits>
#include <utility>

#include "rcdem/config/scenario_bindings.hpp"
#include "rcdem/config/schema.hpp"
#include "rcdem/config/solver_preset.hpp"

namespace rcdem::config {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

KeyDecl real(std::string path, Range range, std::string unit, std::string doc) {
  KeyDecl k;
  k.path = std::move(path);
  k.type = KeyType::Real;
  k.range = range;
  k.unit = std::move(unit);
  k.doc = std::move(doc);
  return k;
}

KeyDecl typed(std::string path, KeyType type, Range range, std::string doc) {
  KeyDecl k;
  k.path = std::move(path);
  k.type = type;
  k.range = range;
  k.doc = std::move(doc);
  return k;
}

// Upper bounds are far beyond any material or test (issue 28): a value above one is a typo or an
// exponent gone wrong, and would otherwise overflow or stall a run instead of being refused here.
KeyDecl positive(std::string path, double max, std::string unit, std::string doc) {
  return real(std::move(path), Range{0.0, max, true, false}, std::move(unit), std::move(doc));
}

KeyDecl choice(std::string path, std::vector<std::string> choices, std::string doc) {
  KeyDecl k;
  k.path = std::move(path);
  k.type = KeyType::String;
  k.choices = std::move(choices);
  k.doc = std::move(doc);
  return k;
}

KeyDecl array(std::string path, int size, Range range, std::string unit, std::string doc) {
  KeyDecl k = typed(std::move(path), KeyType::RealArray, range, std::move(doc));
  k.array_size = size;
  k.unit = std::move(unit);
  return k;
}

// A member's value as a key's, and back (the schema has checked the type and the range).
template <class M>
Value to_value(const M& m) {
  if constexpr (std::is_same_v<M, bool> || std::is_same_v<M, std::string> ||
                std::is_same_v<M, std::vector<double>> ||
                std::is_same_v<M, std::vector<std::string>>)
    return m;
  else if constexpr (std::is_floating_point_v<M>)
    return static_cast<double>(m);
  else if constexpr (std::is_integral_v<M>)
    return static_cast<std::int64_t>(m);
  else
    return std::vector<double>{m.x(), m.y(), m.z()};  // Vec3
}
template <class M>
void from_value(const Value& v, M& m) {
  if constexpr (std::is_same_v<M, bool> || std::is_same_v<M, std::string> ||
                std::is_same_v<M, std::vector<double>> ||
                std::is_same_v<M, std::vector<std::string>>)
    m = std::get<M>(v);
  else if constexpr (std::is_floating_point_v<M>)
    m = std::get<double>(v);
  else if constexpr (std::is_integral_v<M>)
    m = static_cast<M>(std::get<std::int64_t>(v));
  else {
    const auto& a = std::get<std::vector<double>>(v);  // Vec3
    m = Vec3(a[0], a[1], a[2]);
  }
}

// The member of `root` reached through the member pointers `path`, outermost first.
template <class Root, class... Path>
decltype(auto) member_of(Root& root, Path... path) {
  return (root.*....*path);
}

enum class Need { Default, Required };

// Declares keys into a schema and binds them to the members they set.
class Declarations {
 public:
  Declarations(Schema& s, ScenarioBindings& b) : s_(s), b_(b) {}
  void section(std::string path, std::string doc) { s_.section(std::move(path), std::move(doc)); }
  // A key converted by hand in scenario.cpp (it sets several members, or none).
  void unbound(KeyDecl d) { s_.key(std::move(d)); }

  // A key of Scenario, of the plate or bar a [plates.NAME] or [bars.NAME] section is.
  template <class... Path>
  void key(KeyDecl d, Need need, Path... path) {
    bind(std::move(d), need, b_.scenario, path...);
  }
  template <class... Path>
  void plate(KeyDecl d, Need need, Path... path) {
    bind(std::move(d), need, b_.plate, path...);
  }
  template <class... Path>
  void bar(KeyDecl d, Need need, Path... path) {
    bind(std::move(d), need, b_.bar, path...);
  }
  template <class... Path>
  void segment(KeyDecl d, Need need, Path... path) {
    bind(std::move(d), need, b_.segment, path...);
  }
  template <class M, class... Path>
  void segment(KeyDecl d, std::vector<std::pair<std::string, M>> names, Path... path) {
    bind_names(std::move(d), std::move(names), b_.segment, path...);
  }
  template <class... Path>
  void gauge(KeyDecl d, Need need, Path... path) {
    bind(std::move(d), need, b_.gauge, path...);
  }
  template <class M, class... Path>
  void gauge(KeyDecl d, std::vector<std::pair<std::string, M>> names, Path... path) {
    bind_names(std::move(d), std::move(names), b_.gauge, path...);
  }
  // A key whose names stand for values of its member (an enumeration, a flag).
  template <class M, class... Path>
  void key(KeyDecl d, std::vector<std::pair<std::string, M>> names, Path... path) {
    bind_names(std::move(d), std::move(names), b_.scenario, path...);
  }
  template <class M, class... Path>
  void bar(KeyDecl d, std::vector<std::pair<std::string, M>> names, Path... path) {
    bind_names(std::move(d), std::move(names), b_.bar, path...);
  }

 private:
  // The bound path: the key, or its last part for a key of a named section.
  static std::string bound_path(const std::string& key) {
    return key.find('*') == std::string::npos ? key : key.substr(key.rfind('.') + 1);
  }
  // A file's default for a key solver.preset governs is the default preset's value, not the
  // member's (SolverSettings{} is the basic set-up): what print-schema shows is what a file gets.
  static void preset_default(KeyDecl& d) {
    const std::string& preset = solver_preset_names().front();
    if (d.path == "solver.dt_safety")  // for the preset's own estimate
      d.default_value = solver_preset_dt_safety(
          preset, std::get<std::string>(*solver_preset_value(preset, "solver.time_step_estimate")));
    else if (auto v = solver_preset_value(preset, d.path))
      d.default_value = *v;
  }
  // One default-constructed Target for all keys. GCC 12 at -O3 reports the std::string members
  // of a value-initialised Scenario as "may be used uninitialized" in their destructor, a false
  // positive of its -Wmaybe-uninitialized; silenced here only, so that -Werror builds.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
  template <class Target>
  static const Target& defaults_of() {
    static const Target defaults{};
    return defaults;
  }
#pragma GCC diagnostic pop
  template <class Target, class... Path>
  void bind(KeyDecl d, Need need, std::vector<BoundKey<Target>>& out, Path... path) {
    if (need == Need::Default) d.default_value = to_value(member_of(defaults_of<Target>(), path...));
    preset_default(d);
    out.push_back({bound_path(d.path),
                   [path...](const Value& v, Target& t) { from_value(v, member_of(t, path...)); }});
    s_.key(std::move(d));
  }
  template <class M, class Target, class... Path>
  void bind_names(KeyDecl d, std::vector<std::pair<std::string, M>> names,
                  std::vector<BoundKey<Target>>& out, Path... path) {
    for (const auto& [name, value] : names) {
      d.choices.push_back(name);
      if (value == member_of(defaults_of<Target>(), path...)) d.default_value = name;
    }
    preset_default(d);
    out.push_back({bound_path(d.path), [names, path...](const Value& v, Target& t) {
                     for (const auto& [name, value] : names)
                       if (name == std::get<std::string>(v)) member_of(t, path...) = value;
                   }});
    s_.key(std::move(d));
  }
  Schema& s_;
  ScenarioBindings& b_;
};

// The specimen and its particles.
void declare_specimen_and_generation(Declarations& s) {
  using S = Scenario;
  using G = GenerationSettings;
  s.section("specimen", "The specimen's shape. The origin is at a corner; x along the length.");
  s.key(
      choice("specimen.shape", {"box", "beam"},
             "Specimen builder: 'box' (uniaxial cube) or 'beam' (prism, optional central notch)."),
      Need::Required, &S::specimen, &SpecimenSettings::shape);
  s.key(array("specimen.size", 3, Range{0.0, 100.0, true, false}, "m",
              "Outer dimensions [x, y, z]; for a beam [length, width, depth], z vertical."),
        Need::Required, &S::specimen, &SpecimenSettings::size);
  s.key(real("specimen.notch_depth", Range{0.0, 100.0}, "m",
             "Beam only: depth of a central notch cut up from the bottom face (0 = no notch)."),
        Need::Default, &S::specimen, &SpecimenSettings::notch_depth);
  s.key(positive("specimen.notch_width", 100.0, "m", "Beam only: width of the central notch."),
        Need::Default, &S::specimen, &SpecimenSettings::notch_width);

  s.section("generation", "Particle generation (paper 2.3, SPEC 2).");
  s.key(typed("generation.seed", KeyType::Integer, Range{0.0, 9.0e15},
              "Random seed: the same seed gives the same packing."),
        Need::Default, &S::generation, &G::seed);
  s.key(real("generation.porosity", Range{0.0, 1.0, true, true}, "",
             "Target porosity n = 1 - sum(sphere volumes) / specimen volume; mortar is added until "
             "it is reached."),
        Need::Default, &S::generation, &G::porosity);
  s.key(typed("generation.relaxation_iterations", KeyType::Integer, Range{0.0, 100000.0},
              "Overlap-reducing iterations that make the point set homogeneous and isotropic."),
        Need::Default, &S::generation, &G::relaxation_iterations);
  s.key(typed("generation.max_particles", KeyType::Integer, Range{1.0, 1.0e9},
              "Refuse specimens estimated to hold more particles than this (a guard against "
              "typos)."),
        Need::Default, &S::generation, &G::max_particles);
  s.key(real("generation.min_distance_factor", Range{0.0, 1.0, true, false}, "",
             "No centre closer than this times the smaller radius to another centre, or than this "
             "times its own radius to a face."),
        Need::Default, &S::generation, &G::min_distance_factor);

  s.section("generation.aggregate", "Aggregate spheres, placed first.");
  s.key(real("generation.aggregate.content", Range{0.0, 1e5}, "kg/m^3",
             "Aggregate mass per cubic metre of specimen."),
        Need::Default, &S::generation, &G::aggregate_content);
  s.key(positive("generation.aggregate.density", 1e5, "kg/m^3",
                 "Density of the aggregate, turning its mass into a volume of spheres."),
        Need::Default, &S::generation, &G::aggregate_density);
  s.key(positive("generation.aggregate.d_min", 10.0, "m", "Smallest aggregate diameter."),
        Need::Default, &S::generation, &G::aggregate_d_min);
  s.key(positive("generation.aggregate.d_max", 10.0, "m", "Largest aggregate diameter."),
        Need::Default, &S::generation, &G::aggregate_d_max);
  s.key(choice("generation.aggregate.grading", {},
               "Diameter distribution: 'uniform' in diameter, or 'fuller' (mass passing "
               "proportional to d^exponent)."),
        std::vector<std::pair<std::string, Grading>>{{"uniform", Grading::Uniform},
                                                     {"fuller", Grading::Fuller}},
        &S::generation, &G::aggregate_grading);
  s.key(real("generation.aggregate.fuller_exponent", Range{0.05, 2.0}, "",
             "Exponent q of the Fuller grading curve P(d) = (d / d_max)^q, used with grading = "
             "'fuller' (0.5 is Fuller-Thompson; practical curves use 0.3 to 0.7)."),
        Need::Default, &S::generation, &G::fuller_exponent);

  s.section("generation.mortar", "Mortar spheres, added after the aggregate until the porosity.");
  s.key(positive("generation.mortar.d_min", 10.0, "m", "Smallest mortar diameter."), Need::Default,
        &S::generation, &G::mortar_d_min);
  s.key(positive("generation.mortar.d_max", 10.0, "m", "Largest mortar diameter."), Need::Default,
        &S::generation, &G::mortar_d_max);
}

// The contact network, its law and the material.
void declare_contact(Declarations& s) {
  using S = Scenario;
  using C = ContactParameters;
  s.section("tessellation", "VGCM-3D contact network (paper 2.1, SPEC 3).");
  s.key(choice("tessellation.kind", {},
               "'voronoi' (plain, as in the paper) or 'radical' (Laguerre, weighted by radius)."),
        std::vector<std::pair<std::string, TessellationKind>>{
            {"voronoi", TessellationKind::Voronoi}, {"radical", TessellationKind::Radical}},
        &S::tessellation);

  s.section("contact", "Concrete contact parameters, paper Table 2 (SI units).");
  s.key(real("contact.E_bar", Range{1e3, 1e13}, "Pa",
             "E-bar: Young's modulus of the equivalent continuum; k_n = E_bar A_c / d (3)."),
        Need::Default, &S::contact, &C::E_bar);
  s.key(real("contact.alpha", Range{0.0, 100.0, true, false}, "",
             "alpha: k_s = alpha k_n (4); > 0, the BL law divides by k_s."),
        Need::Default, &S::contact, &C::alpha);
  s.key(real("contact.mu_c", Range{0.0, 10.0}, "", "mu_c: contact friction coefficient."),
        Need::Default, &S::contact, &C::mu_c);
  s.key(positive("contact.sigma_nt", 1e10, "Pa",
                 "sigma_n,t: contact tensile strength; F_n,max = sigma_n,t A_c (5)."),
        Need::Default, &S::contact, &C::sigma_nt);
  s.key(positive("contact.tau", 1e10, "Pa", "tau: contact cohesion; C_max = tau A_c (6)."),
        Need::Default, &S::contact, &C::tau);
  s.key(positive("contact.G_fn", 1e8, "J/m^2", "G_f,n: fracture energy in tension."), Need::Default,
        &S::contact, &C::G_fn);
  s.key(positive("contact.G_fs", 1e8, "J/m^2", "G_f,s: fracture energy in shear."), Need::Default,
        &S::contact, &C::G_fs);

  s.key(choice("contact.law", {"BL", "EL", "exponential"},
               "Concrete contact law (contact/laws/law_registry.hpp): 'BL' bilinear softening "
               "(paper 2.4, SPEC 5), 'EL' elastic, 'exponential' scalar damage with "
               "exponential softening regularised by G_f,n (YADE's CPM damage law)."),
        Need::Default, &S::law);

  s.section("material", "Concrete as a continuum (SPEC 6).");
  s.key(positive("material.density", 1e5, "kg/m^3",
                 "Concrete density; a particle's mass is this times its Voronoi cell volume."),
        Need::Default, &S::solver, &SolverSettings::density);
}

// The solver.
void declare_solver(Declarations& s) {
  using S = Scenario;
  using V = SolverSettings;
  s.section("solver", "Explicit time integration (SPEC 6).");
  KeyDecl preset = choice(kSolverPresetKey, solver_preset_names(),
                          "The set-up for the solver keys this file leaves unset (docs/model.md "
                          "6): 'quasi_static', the set-up the bending study passes SPEC 6's "
                          "halving test with (assembled estimate, dt_safety 0.7, damping 0.3, "
                          "rotational inertia x2.5 for particles and x30 for bars); 'basic', "
                          "SPEC 6's plain one (per-body estimate, dt_safety 0.3, damping 0.7, "
                          "true inertia). The defaults below are 'quasi_static''s.");
  preset.default_value = solver_preset_names().front();
  s.unbound(std::move(preset));
  s.key(choice("solver.time_step_estimate", {},
               "How the stable time step is estimated (SPEC 6): 'per_body', min over bodies of "
               "sqrt(m / sum k) with each body's own springs; 'assembled', the critical step "
               "2 / omega_max of the whole assembly (Lanczos on M^-1 K; a few seconds at set-up)."),
        std::vector<std::pair<std::string, TimeStepEstimate>>{
            {"per_body", TimeStepEstimate::PerBody}, {"assembled", TimeStepEstimate::Assembled}},
        &S::solver, &V::estimate);
  s.key(real("solver.dt_safety", Range{0.0, 0.8, true, false}, "",
             "Time step = this times the estimate: at most 0.5 with 'per_body', 0.8 with "
             "'assembled' (SPEC 6). Unset, it follows the estimate: 0.7 with 'assembled' "
             "(preset 'quasi_static'), 0.3 with 'per_body'."),
        Need::Default, &S::solver, &V::dt_safety);
  s.key(real("solver.time_step", Range{0.0, 1.0}, "s",
             "Fixed time step; 0 = automatic, else at least 1e-12 s. Refused above the estimate "
             "times 0.5 ('per_body') "
             "or 0.8 ('assembled')."),
        Need::Default, &S::solver, &V::time_step);
  s.key(real("solver.damping", Range{0.0, 1.0, false, true}, "",
             "Local non-viscous (Cundall) damping coefficient."),
        Need::Default, &S::solver, &V::damping);
  s.key(real("solver.mass_scaling", Range{1.0, 1.0e8}, "",
             "Multiply every mass and inertia by this (a larger stable step for quasi-static "
             "runs)."),
        Need::Default, &S::solver, &V::mass_scaling);
  s.key(real("solver.added_mass_limit", Range{0.0, 0.1}, "",
             "Selective mass scaling: the bodies whose own stable step is shortest get heavier "
             "(mass and moments of inertia alike) until every body reaches a common step, the "
             "longest whose added mass is at most this fraction of the total (0.005 = 0.5%). "
             "0 = off. The run's header and summary.json report the bodies, factors and mass."),
        Need::Default, &S::solver, &V::added_mass_limit);
  s.key(real("solver.bar_rotational_inertia_scaling", Range{1.0, 1.0e4}, "",
             "Multiply the moments of inertia of the bars' cylinders by this: with coarse "
             "particles the bars' rotation (torsion, then bending) sets the time step, and a "
             "quasi-static result does not depend on it."),
        Need::Default, &S::solver, &V::bar_rotational_inertia_scaling);
  s.key(real("solver.particle_rotational_inertia_scaling", Range{1.0, 100.0}, "",
             "Multiply the particles' moments of inertia (2/5 m r^2) by this: their rotation, not "
             "their translation, sets the time step (1.46x shorter in the case study), and a "
             "quasi-static result does not depend on it."),
        Need::Default, &S::solver, &V::particle_rotational_inertia_scaling);
  s.key(typed("solver.condense_elastic_contacts", KeyType::Boolean, Range{},
              "Evaluate a concrete contact whose local points are all intact and stay below "
              "their elastic limits from its sums (the same force and moment as its points give, "
              "to rounding) instead of visiting its points: faster, same results. false: visit "
              "every point every step."),
        Need::Default, &S::solver, &V::condense_elastic_contacts);
  s.key(typed("solver.hold_unloading_contacts", KeyType::Boolean, Range{},
              "With condense_elastic_contacts: evaluate a damaged concrete contact whose local "
              "points all stay inside their envelopes (unloading or reloading elastically) from "
              "sums kept since it entered them, instead of visiting its points. The same results "
              "to rounding; a cracked specimen's step is faster, and snapshots and checkpoints "
              "change nothing it computes (docs/model.md). false: visit every damaged contact's "
              "points every step."),
        Need::Default, &S::solver, &V::hold_unloading_contacts);
  s.key(typed("solver.hold_softening_contacts", KeyType::Boolean, Range{},
              "With hold_unloading_contacts: hold too a damaged contact whose unbroken points all "
              "soften along their normal envelope while they keep opening (docs/model.md). The "
              "same results to rounding; faster where cracks open steadily (a pulled cube: 1.14x), "
              "no slower where they open and close from step to step (a cracked beam: 1.03x: a "
              "contact whose softening hold ends within 8 steps waits 64 visits before the next). "
              "false: only contacts whose points stay inside their envelopes are held."),
        Need::Default, &S::solver, &V::hold_softening_contacts);
  s.key(typed("solver.hold_intact_contacts", KeyType::Boolean, Range{},
              "With hold_unloading_contacts: hold too an intact concrete contact that the "
              "condensation's bound sends to its points (near an elastic limit), while its points "
              "stay below their limits by the held contacts' own bound, which starts from the "
              "points and is tighter (docs/model.md). The same results to rounding; a cracked "
              "specimen's step is faster. false: such contacts visit their points."),
        Need::Default, &S::solver, &V::hold_intact_contacts);
}

// The plates.
void declare_plates(Declarations& s) {
  using P = PlateSettings;
  s.section("plates", "Rigid plates: one [plates.NAME] table per plate, NAME of your choice.");
  s.section("plates.*",
            "A rigid plate on one face of the specimen (platen, support, loading plate).");
  s.unbound(choice("plates.*.face", {"x-", "x+", "y-", "y+", "z-", "z+"},
                   "The specimen face the plate lies on; its normal points into the specimen."));
  s.plate(array("plates.*.extent", 4, Range{}, "m",
                "Plate rectangle [u_min, u_max, v_min, v_max] in the face's two other axes "
                "(in x, y, z order); [] = the whole face."),
          Need::Default, &P::extent);
  s.plate(real("plates.*.velocity", Range{-1e3, 1e3}, "m/s",
               "Prescribed velocity along the face's axis (+ = towards +axis): displacement "
               "control."),
          Need::Default, &P::velocity);
  s.plate(real("plates.*.ramp_time", Range{0.0, 1e3}, "s",
               "The velocity rises smoothly from 0 over this time, to avoid a shock."),
          Need::Default, &P::ramp_time);
  s.plate(typed("plates.*.glued", KeyType::Boolean, Range{},
                "Glued: the contact carries tension and shear elastically (tension tests). "
                "Otherwise unilateral with Coulomb friction."),
          Need::Default, &P::glued);
  s.plate(real("plates.*.friction", Range{0.0, 10.0}, "",
               "Coulomb friction coefficient of an unglued plate (0 = frictionless)."),
          Need::Default, &P::friction);
}

// A loading program's segments, for a plate (`owner` "plates") or a pulled bar ("bars").
void declare_program(Declarations& s, const std::string& owner) {
  using G = SegmentSettings;
  const std::string p = owner + ".*.program";
  s.section(p, "A loading program: its segments, one [" + owner +
                   ".NAME.program.SEGMENT] table each, run in the file's order (docs/model.md 13); "
                   "instead of a constant velocity.");
  s.section(p + ".*", "One segment of a loading program.");
  s.segment(choice(p + ".*.kind", {},
                   "'velocity' (for a duration, or to the end), 'displacement' (to a target at a "
                   "speed), 'load' (to a target load at a speed, either way), 'hold' (still for "
                   "a duration), 'force' (a servo brings the load to a target and holds it there "
                   "for a duration), "
                   "'cycles' (count times: to a displacement amplitude growing by "
                   "amplitude_step, then back to the load unload_to)."),
            std::vector<std::pair<std::string, SegmentKind>>{
                {"velocity", SegmentKind::Velocity}, {"displacement", SegmentKind::Displacement},
                {"load", SegmentKind::Load},         {"hold", SegmentKind::Hold},
                {"force", SegmentKind::Force},       {"cycles", SegmentKind::Cycles}},
            &G::kind);
  s.segment(real(p + ".*.velocity", Range{-1e3, 1e3}, "m/s",
                 "velocity: the velocity (plates: along +axis; bars: along the pull)."),
            Need::Default, &G::velocity);
  s.segment(real(p + ".*.duration", Range{0.0, 1e3}, "s",
                 "velocity, hold, force: how long (velocity: 0 = until the run stops)."),
            Need::Default, &G::duration);
  s.segment(real(p + ".*.target", Range{-1e9, 1e9}, "m or N",
                 "displacement: the displacement to reach (m, since t = 0); load, force: the "
                 "load (N)."),
            Need::Default, &G::target);
  s.segment(real(p + ".*.speed", Range{0.0, 1e3}, "m/s",
                 "displacement, load, cycles: the speed of the move; force: the servo's "
                 "largest."),
            Need::Default, &G::speed);
  s.segment(typed(p + ".*.count", KeyType::Integer, Range{1.0, 1e4}, "cycles: how many."),
            Need::Default, &G::count);
  s.segment(real(p + ".*.amplitude", Range{-100.0, 100.0}, "m",
                 "cycles: the first cycle's peak displacement (since t = 0)."),
            Need::Default, &G::amplitude);
  s.segment(real(p + ".*.amplitude_step", Range{-100.0, 100.0}, "m",
                 "cycles: each cycle's peak beyond the one before."),
            Need::Default, &G::amplitude_step);
  s.segment(real(p + ".*.unload_to", Range{-1e9, 1e9}, "N",
                 "cycles: the load each cycle unloads to before the next."),
            Need::Default, &G::unload_to);
  s.segment(real(p + ".*.response_time", Range{0.0, 1e3}, "s",
                 "force: the servo's time constant: velocity = (target - load) / (stiffness x "
                 "response_time), at most speed."),
            Need::Default, &G::response_time);
  s.segment(real(p + ".*.tolerance", Range{0.0, 1.0, true, false}, "",
                 "force: the hold's duration counts from the first step the load is within this "
                 "fraction of the target."),
            Need::Default, &G::tolerance);
  s.segment(real(p + ".*.stiffness", Range{0.0, 1e15}, "N/m",
                 "force: the specimen's stiffness the servo assumes; 0: the secant load / "
                 "displacement at the segment's start."),
            Need::Default, &G::stiffness);
}

// Gauges: measured displacements, each a history column.
void declare_gauges(Declarations& s) {
  using G = GaugeSettings;
  s.section("gauges", "Gauges: one [gauges.NAME] table per gauge, each a history.csv column "
                      "gauge_NAME_m (docs/model.md 12).");
  s.section("gauges.*", "A displacement gauge (an LVDT) or an opening gauge (a clip gauge).");
  s.gauge(choice("gauges.*.kind", {},
                 "'displacement': the material at point, along direction, less the mean "
                 "displacement of the relative_to plates; 'opening': the material at to against "
                 "the material at point."),
          std::vector<std::pair<std::string, GaugeKind>>{{"displacement", GaugeKind::Displacement},
                                                         {"opening", GaugeKind::Opening}},
          &G::kind);
  s.gauge(array("gauges.*.point", 3, Range{}, "m", "The measured point [x, y, z]."),
          Need::Required, &G::point);
  s.gauge(array("gauges.*.to", 3, Range{}, "m",
                "Opening gauges: the second point [x, y, z]; the opening is positive as the two "
                "move apart."),
          Need::Default, &G::to);
  s.gauge(choice("gauges.*.direction", {},
                 "Which component: 'x', 'y', 'z', 'along' (opening: along the line from point to "
                 "to) or 'auto' (displacement: 'z'; opening: 'along')."),
          std::vector<std::pair<std::string, int>>{{"auto", G::kAuto},
                                                   {"x", 0},
                                                   {"y", 1},
                                                   {"z", 2},
                                                   {"along", G::kAlong}},
          &G::axis);
  s.gauge(typed("gauges.*.relative_to", KeyType::StringArray, Range{},
                "Displacement gauges: plates on the same axis whose mean displacement is "
                "subtracted (the supports, for a deflection)."),
          Need::Default, &G::relative_to);
  s.gauge(real("gauges.*.radius", Range{0.0, 10.0}, "m",
               "The material at a point: the uniform-strain field fitted to the concrete particles "
               "whose centres lie within this distance of it (at least 4, spanning 3 "
               "directions), at the point; 0: the nearest particle, carrying the point rigidly."),
          Need::Default, &G::radius);
}

// What controls the test and when it stops.
void declare_loading_and_stop(Declarations& s) {
  using S = Scenario;
  using L = LoadingRateSettings;
  using T = StopSettings;
  s.section("loading", "Which plate is the load and displacement of the test.");
  s.key(typed("loading.control_plate", KeyType::String, Range{},
              "Name of the plate whose reaction is the load and whose displacement is "
              "controlled."),
        Need::Default, &S::control_plate);
  s.key(typed("loading.control_plates", KeyType::StringArray, Range{},
              "Or: the plates whose reactions sum to the load (four-point bending's two loading "
              "plates); the displacement is their mean."),
        Need::Default, &S::control_plates);
  s.key(typed("loading.displacement_gauge", KeyType::String, Range{},
              "A gauge (a [gauges.NAME] section) whose value is the test's displacement instead "
              "of the control's: in summary.json, the stop rules, the progress line and the "
              "load-displacement plot."),
        Need::Default, &S::displacement_gauge);
  s.key(typed("loading.control_bar", KeyType::String, Range{},
              "Or: name of a pulled bar (pull_velocity > 0) whose pull-out force is the load."),
        Need::Default, &S::control_bar);
  s.key(typed("loading.adaptive_rate", KeyType::Boolean, Range{},
              "Adaptive loading rate (docs/model.md 6): every prescribed plate and pulled bar "
              "moves at a factor x its velocity, the factor rising while the kinetic energy is "
              "small against the strain energy and no crack bursts, and falling back to 1 when "
              "either fails. Displacement stays the control variable."),
        Need::Default, &S::loading_rate, &L::adaptive);
  s.key(real("loading.max_rate_factor", Range{1.0, 100.0}, "",
             "Adaptive rate: the largest factor on the set velocities."),
        Need::Default, &S::loading_rate, &L::max_factor);
  s.key(real("loading.kinetic_ratio", Range{0.0, 1.0, false, true}, "",
             "Adaptive rate: above this kinetic / strain energy the factor falls; below half of "
             "it, it rises."),
        Need::Default, &S::loading_rate, &L::kinetic_ratio);
  s.key(real("loading.damage_work_ratio", Range{0.0, kInf, false, true}, "",
             "Adaptive rate: a crack burst, when more than this fraction of the work done over "
             "the last check (20 steps) is dissipated by damage: the factor falls."),
        Need::Default, &S::loading_rate, &L::damage_work_ratio);
  s.key(real("loading.rate_doubling_time", Range{0.0, 1e3, true, false}, "s",
             "Adaptive rate: the factor rises by about 2x over this time at most, and falls 2x "
             "in a quarter of it (about one period of the specimen's first mode or more)."),
        Need::Default, &S::loading_rate, &L::doubling_time);

  s.section("stop", "Stop rules: the run ends when any active rule triggers (0 = off).");
  s.key(real("stop.displacement", Range{0.0, 100.0}, "m",
             "Stop when the control plate has moved this far."),
        Need::Default, &S::stop, &T::displacement);
  s.key(real("stop.load_drop", Range{0.0, 1.0, false, true}, "",
             "Stop once the load has fallen below this fraction of its peak, after the peak."),
        Need::Default, &S::stop, &T::load_drop);
  s.key(real("stop.post_peak_displacement", Range{0.0, 100.0}, "m",
             "Stop once the control plate has moved this far past the peak load's position."),
        Need::Default, &S::stop, &T::post_peak_displacement);
  s.key(real("stop.time", Range{0.0, 1e6}, "s", "Stop at this simulated time."), Need::Default,
        &S::stop, &T::time);
  s.key(typed("stop.steps", KeyType::Integer, Range{0.0, 1.0e12}, "Stop after this many steps."),
        Need::Default, &S::stop, &T::steps);
}

// The bars.
void declare_bars(Declarations& s) {
  using B = BarSettings;
  s.section("bars", "Steel bars (paper 2.5-2.6, SPEC 7-8): one [bars.NAME] table per bar.");
  s.section("bars.*",
            "A straight steel bar: a chain of rigid cylinders with lumped interaction nodes.");
  s.bar(array("bars.*.start", 3, Range{}, "m",
              "First end of a straight bar's axis [x, y, z] (or give a path)."),
        Need::Default, &B::start);
  s.bar(array("bars.*.end", 3, Range{}, "m", "Last end of a straight bar's axis [x, y, z]."),
        Need::Default, &B::end);
  KeyDecl path = array("bars.*.path", 0, Range{}, "m",
                       "A bent bar instead: its corner points [x0, y0, z0, x1, y1, z1, ...] in "
                       "order (hooks, stirrups; docs/model.md 14).");
  path.array_step = 3;
  s.bar(path, Need::Default, &B::path);
  s.bar(typed("bars.*.closed", KeyType::Boolean, Range{},
              "A bent bar that closes on itself (a stirrup): its last point joins its first."),
        Need::Default, &B::closed);
  s.bar(real("bars.*.bend_radius", Range{0.0, 10.0}, "m",
             "A bent bar's bends: the radius of its axis round each corner (0: 2 D)."),
        Need::Default, &B::bend_radius);
  s.bar(positive("bars.*.diameter", 10.0, "m", "Bar diameter D."), Need::Required, &B::diameter);
  s.bar(positive("bars.*.cylinder_length", 100.0, "m",
                 "Target length of the rigid cylinders (the bar is cut into equal ones)."),
        Need::Default, &B::cylinder_length);
  s.bar(real("bars.*.E", Range{1e3, 1e13}, "Pa", "Young's modulus of the steel."), Need::Default,
        &B::E);
  s.bar(real("bars.*.nu", Range{0.0, 0.5, false, true}, "",
             "Poisson's ratio of the steel (G = E / (2 (1 + nu)))."),
        Need::Default, &B::nu);
  s.bar(positive("bars.*.f_y", 1e11, "Pa", "Yield stress: the axial force plateaus at f_y A."),
        Need::Required, &B::f_y);
  s.bar(positive("bars.*.density", 1e5, "kg/m^3", "Density of the steel."), Need::Default,
        &B::density);
  s.bar(choice("bars.*.interface", {},
               "Steel-concrete interface: 'EL' elastic, 'NL-A' softening with the concrete's "
               "parameters, 'NL-B' the same with sigma_n,t and tau halved (paper 3, Table 3); the "
               "law: interface_softening."),
        std::vector<std::pair<std::string, InterfaceLaw>>{
            {"EL", InterfaceLaw::EL}, {"NL-A", InterfaceLaw::NL_A}, {"NL-B", InterfaceLaw::NL_B}},
        &B::interface);
  s.bar(choice("bars.*.interface_softening", {"BL", "exponential"},
               "The softening law of an NL-A or NL-B interface, one of contact.law's softening "
               "laws: 'BL' bilinear softening or 'exponential'."),
        Need::Default, &B::interface_softening);
  s.bar(real("bars.*.interface_strength_scale", Range{0.0, 1e6, true, false}, "",
             "Multiplies sigma_n,t and tau of a nonlinear interface (NL-A, NL-B; after NL-B's "
             "halving): "
             "for studies of the bond beyond the paper's two variants."),
        Need::Default, &B::interface_strength_scale);
  s.bar(real("bars.*.interface_energy_scale", Range{0.0, 1e6, true, false}, "",
             "Multiplies G_fn and G_fs of a nonlinear interface (NL-A, NL-B)."),
        Need::Default, &B::interface_energy_scale);
  s.bar(real("bars.*.pull_velocity", Range{0.0, 1e3}, "m/s",
             "Pull-out: the bar's first cylinder (at 'start') is moved at this speed along end -> "
             "start, its rotation held (0 = not pulled)."),
        Need::Default, &B::pull_velocity);
  s.bar(real("bars.*.pull_ramp_time", Range{0.0, 1e3}, "s",
             "The pull speed rises smoothly from 0 over this time."),
        Need::Default, &B::pull_ramp_time);
  s.bar(real("bars.*.sphere_spacing", Range{0.0, 10.0}, "m",
             "Spacing of the interface spheres along each cylinder; 0 = D / 2."),
        Need::Default, &B::sphere_spacing);
}

// The outputs.
void declare_output(Declarations& s) {
  using S = Scenario;
  using O = OutputSettings;
  s.section("output", "What is written and how.");
  s.key(typed("output.history_rows", KeyType::Integer, Range{10.0, 1.0e7},
              "About this many rows of history.csv over the run."),
        Need::Default, &S::output, &O::history_rows);
  s.key(typed("output.snapshots", KeyType::Integer, Range{0.0, 1.0e5},
              "About this many VTU snapshots over the run (plus the first and the last)."),
        Need::Default, &S::output, &O::snapshots);
  s.key(choice("output.vtu_encoding", {},
               "VTU data encoding: 'binary' (base64, compact) or 'ascii' (readable)."),
        std::vector<std::pair<std::string, bool>>{{"binary", true}, {"ascii", false}}, &S::output,
        &O::binary_vtu);
  s.key(typed("output.write_facets", KeyType::Boolean, Range{},
              "Write facets.vtu (the contact facets as polygons)."),
        Need::Default, &S::output, &O::write_facets);
}

struct Built {
  Schema schema;
  ScenarioBindings bindings;
};

Built build() {
  Built b;
  Declarations s(b.schema, b.bindings);
  declare_specimen_and_generation(s);
  declare_contact(s);
  declare_solver(s);
  declare_plates(s);
  declare_program(s, "plates");
  declare_loading_and_stop(s);
  declare_gauges(s);
  declare_bars(s);
  declare_program(s, "bars");
  declare_output(s);
  return b;
}

const Built& built() {
  static const Built b = build();
  return b;
}

}  // namespace

const Schema& scenario_schema() { return built().schema; }

const ScenarioBindings& scenario_bindings() { return built().bindings; }

}  // namespace rcdem::config
