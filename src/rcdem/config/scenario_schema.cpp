// The declaration of every scenario key: one place, read by the loader, print-schema and the docs.
#include <limits>

#include "rcdem/config/schema.hpp"

namespace rcdem::config {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

KeyDecl real(std::string path, std::optional<double> def, Range range, std::string unit,
             std::string doc) {
  KeyDecl k;
  k.path = std::move(path);
  k.type = KeyType::Real;
  if (def) k.default_value = *def;
  k.range = range;
  k.unit = std::move(unit);
  k.doc = std::move(doc);
  return k;
}

KeyDecl typed(std::string path, KeyType type, Value def, Range range, std::string doc) {
  KeyDecl k;
  k.path = std::move(path);
  k.type = type;
  k.default_value = std::move(def);
  k.range = range;
  k.doc = std::move(doc);
  return k;
}

// Upper bounds are far beyond any material or test (issue 28): a value above one is a typo or an
// exponent gone wrong, and would otherwise overflow or stall a run instead of being refused here.
KeyDecl positive(std::string path, std::optional<double> def, double max, std::string unit,
                 std::string doc) {
  return real(std::move(path), def, Range{0.0, max, true, false}, std::move(unit), std::move(doc));
}

KeyDecl choice(std::string path, std::optional<std::string> def, std::vector<std::string> choices,
               std::string doc) {
  KeyDecl k;
  k.path = std::move(path);
  k.type = KeyType::String;
  if (def) k.default_value = *def;
  k.choices = std::move(choices);
  k.doc = std::move(doc);
  return k;
}

// The specimen and its particles.
void declare_specimen_and_generation(Schema& s) {
  s.section("specimen", "The specimen's shape. The origin is at a corner; x along the length.");
  s.key(
      choice("specimen.shape", std::nullopt, {"box", "beam"},
             "Specimen builder: 'box' (uniaxial cube) or 'beam' (prism, optional central notch)."));
  {
    KeyDecl k = typed("specimen.size", KeyType::RealArray, std::vector<double>{},
                      Range{0.0, 100.0, true, false},
                      "Outer dimensions [x, y, z]; for a beam [length, width, depth], z vertical.");
    k.default_value.reset();  // required
    k.array_size = 3;
    k.unit = "m";
    s.key(k);
  }
  s.key(real("specimen.notch_depth", 0.0, Range{0.0, 100.0}, "m",
             "Beam only: depth of a central notch cut up from the bottom face (0 = no notch)."));
  s.key(positive("specimen.notch_width", 0.003, 100.0, "m",
                 "Beam only: width of the central notch."));

  s.section("generation", "Particle generation (paper 2.3, SPEC 2).");
  s.key(typed("generation.seed", KeyType::Integer, std::int64_t{1}, Range{0.0, 9.0e15},
              "Random seed: the same seed gives the same packing."));
  s.key(real("generation.porosity", 0.10, Range{0.0, 1.0, true, true}, "",
             "Target porosity n = 1 - sum(sphere volumes) / specimen volume; mortar is added until "
             "it is reached."));
  s.key(typed("generation.relaxation_iterations", KeyType::Integer, std::int64_t{300},
              Range{0.0, 100000.0},
              "Overlap-reducing iterations that make the point set homogeneous and isotropic."));
  s.key(typed(
      "generation.max_particles", KeyType::Integer, std::int64_t{5000000}, Range{1.0, 1.0e9},
      "Refuse specimens estimated to hold more particles than this (a guard against typos)."));
  s.key(real("generation.min_distance_factor", 0.5, Range{0.0, 1.0, true, false}, "",
             "No centre closer than this times the smaller radius to another centre, or than this "
             "times its own radius to a face."));

  s.section("generation.aggregate", "Aggregate spheres, placed first.");
  s.key(real("generation.aggregate.content", 568.5, Range{0.0, 1e5}, "kg/m^3",
             "Aggregate mass per cubic metre of specimen."));
  s.key(positive("generation.aggregate.density", 2700.0, 1e5, "kg/m^3",
                 "Density of the aggregate, turning its mass into a volume of spheres."));
  s.key(positive("generation.aggregate.d_min", 0.008, 10.0, "m", "Smallest aggregate diameter."));
  s.key(positive("generation.aggregate.d_max", 0.012, 10.0, "m", "Largest aggregate diameter."));
  s.key(choice("generation.aggregate.grading", std::string("uniform"), {"uniform", "fuller"},
               "Diameter distribution: 'uniform' in diameter, or 'fuller' (mass passing "
               "proportional to d^exponent)."));
  s.key(real("generation.aggregate.fuller_exponent", 0.5, Range{0.05, 2.0}, "",
             "Exponent q of the Fuller grading curve P(d) = (d / d_max)^q, used with grading = "
             "'fuller' (0.5 is Fuller-Thompson; practical curves use 0.3 to 0.7)."));

  s.section("generation.mortar", "Mortar spheres, added after the aggregate until the porosity.");
  s.key(positive("generation.mortar.d_min", 0.008, 10.0, "m", "Smallest mortar diameter."));
  s.key(positive("generation.mortar.d_max", 0.009, 10.0, "m", "Largest mortar diameter."));
}

// The contact network, its law and the solver.
void declare_contact_and_solver(Schema& s) {
  s.section("tessellation", "VGCM-3D contact network (paper 2.1, SPEC 3).");
  s.key(choice("tessellation.kind", std::string("voronoi"), {"voronoi", "radical"},
               "'voronoi' (plain, as in the paper) or 'radical' (Laguerre, weighted by radius)."));

  s.section("contact", "Concrete contact parameters, paper Table 2 (SI units).");
  s.key(real("contact.E_bar", 48.7e9, Range{1e3, 1e13}, "Pa",
             "E-bar: Young's modulus of the equivalent continuum; k_n = E_bar A_c / d (3)."));
  s.key(real("contact.alpha", 0.3, Range{0.0, 100.0, true, false}, "",
             "alpha: k_s = alpha k_n (4); > 0, the BL law divides by k_s."));
  s.key(real("contact.mu_c", 0.5, Range{0.0, 10.0}, "", "mu_c: contact friction coefficient."));
  s.key(positive("contact.sigma_nt", 4.15e6, 1e10, "Pa",
                 "sigma_n,t: contact tensile strength; F_n,max = sigma_n,t A_c (5)."));
  s.key(positive("contact.tau", 21.0e6, 1e10, "Pa", "tau: contact cohesion; C_max = tau A_c (6)."));
  s.key(positive("contact.G_fn", 9.002, 1e8, "J/m^2", "G_f,n: fracture energy in tension."));
  s.key(positive("contact.G_fs", 2380.785, 1e8, "J/m^2", "G_f,s: fracture energy in shear."));

  s.key(choice("contact.law", std::string("BL"), {"BL", "EL", "exponential"},
               "Concrete contact law (contact/laws/law_registry.hpp): 'BL' bilinear softening "
               "(paper 2.4, SPEC 5), 'EL' elastic, 'exponential' scalar damage with "
               "exponential softening regularised by G_f,n (YADE's CPM damage law)."));

  s.section("material", "Concrete as a continuum (SPEC 6).");
  s.key(positive("material.density", 2400.0, 1e5, "kg/m^3",
                 "Concrete density; a particle's mass is this times its Voronoi cell volume."));

  s.section("solver", "Explicit time integration (SPEC 6).");
  s.key(
      choice("solver.time_step_estimate", std::string("per_body"), {"per_body", "assembled"},
             "How the stable time step is estimated (SPEC 6): 'per_body', min over bodies of "
             "sqrt(m / sum k) with each body's own springs; 'assembled', the critical step "
             "2 / omega_max of the whole assembly (Lanczos on M^-1 K; a few seconds at set-up)."));
  s.key(real("solver.dt_safety", 0.3, Range{0.0, 0.8, true, false}, "",
             "Time step = this times the estimate: at most 0.5 with 'per_body', 0.8 with "
             "'assembled' (SPEC 6)."));
  s.key(real("solver.time_step", 0.0, Range{0.0, 1.0}, "s",
             "Fixed time step; 0 = automatic, else at least 1e-12 s. Refused above the estimate "
             "times 0.5 ('per_body') "
             "or 0.8 ('assembled')."));
  s.key(real("solver.damping", 0.7, Range{0.0, 1.0, false, true}, "",
             "Local non-viscous (Cundall) damping coefficient."));
  s.key(real(
      "solver.mass_scaling", 1.0, Range{1.0, 1.0e8}, "",
      "Multiply every mass and inertia by this (a larger stable step for quasi-static runs)."));
  s.key(real("solver.added_mass_limit", 0.0, Range{0.0, 0.1}, "",
             "Selective mass scaling: the bodies whose own stable step is shortest get heavier "
             "(mass and moments of inertia alike) until every body reaches a common step, the "
             "longest whose added mass is at most this fraction of the total (0.005 = 0.5%). "
             "0 = off. The run's header and summary.json report the bodies, factors and mass."));
  s.key(real("solver.bar_rotational_inertia_scaling", 1.0, Range{1.0, 1.0e4}, "",
             "Multiply the moments of inertia of the bars' cylinders by this: with coarse "
             "particles the bars' rotation (torsion, then bending) sets the time step, and a "
             "quasi-static result does not depend on it."));
  s.key(real("solver.particle_rotational_inertia_scaling", 1.0, Range{1.0, 100.0}, "",
             "Multiply the particles' moments of inertia (2/5 m r^2) by this: their rotation, not "
             "their translation, sets the time step (1.46x shorter in the case study), and a "
             "quasi-static result does not depend on it."));
  s.key(typed("solver.condense_elastic_contacts", KeyType::Boolean, true, Range{},
              "Evaluate a concrete contact whose local points are all intact and stay below "
              "their elastic limits from its sums (the same force and moment as its points give, "
              "to rounding) instead of visiting its points: faster, same results. false: visit "
              "every point every step."));
}

// The plates, what controls the test and when it stops.
void declare_plates_loading_and_stop(Schema& s) {
  s.section("plates", "Rigid plates: one [plates.NAME] table per plate, NAME of your choice.");
  s.section("plates.*",
            "A rigid plate on one face of the specimen (platen, support, loading plate).");
  s.key(choice("plates.*.face", std::nullopt, {"x-", "x+", "y-", "y+", "z-", "z+"},
               "The specimen face the plate lies on; its normal points into the specimen."));
  {
    KeyDecl k = typed("plates.*.extent", KeyType::RealArray, std::vector<double>{}, Range{},
                      "Plate rectangle [u_min, u_max, v_min, v_max] in the face's two other axes "
                      "(in x, y, z order); [] = the whole face.");
    k.array_size = 4;
    k.unit = "m";
    s.key(k);
  }
  s.key(
      real("plates.*.velocity", 0.0, Range{-1e3, 1e3}, "m/s",
           "Prescribed velocity along the face's axis (+ = towards +axis): displacement control."));
  s.key(real("plates.*.ramp_time", 0.0, Range{0.0, 1e3}, "s",
             "The velocity rises smoothly from 0 over this time, to avoid a shock."));
  s.key(typed("plates.*.glued", KeyType::Boolean, false, Range{},
              "Glued: the contact carries tension and shear elastically (tension tests). Otherwise "
              "unilateral with Coulomb friction."));
  s.key(real("plates.*.friction", 0.0, Range{0.0, 10.0}, "",
             "Coulomb friction coefficient of an unglued plate (0 = frictionless)."));

  s.section("loading", "Which plate is the load and displacement of the test.");
  s.key(
      typed("loading.control_plate", KeyType::String, std::string(""), Range{},
            "Name of the plate whose reaction is the load and whose displacement is controlled."));
  s.key(typed("loading.control_bar", KeyType::String, std::string(""), Range{},
              "Or: name of a pulled bar (pull_velocity > 0) whose pull-out force is the load."));
  s.key(typed("loading.adaptive_rate", KeyType::Boolean, false, Range{},
              "Adaptive loading rate (docs/model.md 6): every prescribed plate and pulled bar "
              "moves at a factor x its velocity, the factor rising while the kinetic energy is "
              "small against the strain energy and no crack bursts, and falling back to 1 when "
              "either fails. Displacement stays the control variable."));
  s.key(real("loading.max_rate_factor", 4.0, Range{1.0, 100.0}, "",
             "Adaptive rate: the largest factor on the set velocities."));
  s.key(real("loading.kinetic_ratio", 0.01, Range{0.0, 1.0, false, true}, "",
             "Adaptive rate: above this kinetic / strain energy the factor falls; below half of "
             "it, it rises."));
  s.key(real("loading.damage_work_ratio", 0.5, Range{0.0, kInf, false, true}, "",
             "Adaptive rate: a crack burst, when more than this fraction of the work done over "
             "the last check (20 steps) is dissipated by damage: the factor falls."));
  s.key(real("loading.rate_doubling_time", 2e-3, Range{0.0, 1e3, true, false}, "s",
             "Adaptive rate: the factor rises by about 2x over this time at most, and falls 2x "
             "in a quarter of it (about one period of the specimen's first mode or more)."));

  s.section("stop", "Stop rules: the run ends when any active rule triggers (0 = off).");
  s.key(real("stop.displacement", 0.0, Range{0.0, 100.0}, "m",
             "Stop when the control plate has moved this far."));
  s.key(real("stop.load_drop", 0.0, Range{0.0, 1.0, false, true}, "",
             "Stop once the load has fallen below this fraction of its peak, after the peak."));
  s.key(real("stop.post_peak_displacement", 0.0, Range{0.0, 100.0}, "m",
             "Stop once the control plate has moved this far past the peak load's position."));
  s.key(real("stop.time", 0.0, Range{0.0, 1e6}, "s", "Stop at this simulated time."));
  s.key(typed("stop.steps", KeyType::Integer, std::int64_t{0}, Range{0.0, 1.0e12},
              "Stop after this many steps."));
}

// The bars and the outputs.
void declare_bars_and_output(Schema& s) {
  s.section("bars", "Steel bars (paper 2.5-2.6, SPEC 7-8): one [bars.NAME] table per bar.");
  s.section("bars.*",
            "A straight steel bar: a chain of rigid cylinders with lumped interaction nodes.");
  {
    KeyDecl k = typed("bars.*.start", KeyType::RealArray, Value{}, Range{},
                      "First end of the bar's axis [x, y, z].");
    k.default_value.reset();
    k.array_size = 3;
    k.unit = "m";
    s.key(k);
    k.path = "bars.*.end";
    k.doc = "Last end of the bar's axis [x, y, z].";
    s.key(k);
  }
  s.key(positive("bars.*.diameter", std::nullopt, 10.0, "m", "Bar diameter D."));
  s.key(positive("bars.*.cylinder_length", 0.032, 100.0, "m",
                 "Target length of the rigid cylinders (the bar is cut into equal ones)."));
  s.key(real("bars.*.E", 200.0e9, Range{1e3, 1e13}, "Pa", "Young's modulus of the steel."));
  s.key(real("bars.*.nu", 0.3, Range{0.0, 0.5, false, true}, "",
             "Poisson's ratio of the steel (G = E / (2 (1 + nu)))."));
  s.key(positive("bars.*.f_y", std::nullopt, 1e11, "Pa",
                 "Yield stress: the axial force plateaus at f_y A."));
  s.key(positive("bars.*.density", 7850.0, 1e5, "kg/m^3", "Density of the steel."));
  s.key(choice(
      "bars.*.interface", std::string("NL-B"), {"EL", "NL-A", "NL-B"},
      "Steel-concrete interface: 'EL' elastic, 'NL-A' softening with the concrete's "
      "parameters, 'NL-B' the same with sigma_n,t and tau halved (paper 3, Table 3); the law: "
      "interface_softening."));
  s.key(choice("bars.*.interface_softening", std::string("BL"), {"BL", "exponential"},
               "The softening law of an NL-A or NL-B interface, one of contact.law's softening "
               "laws: 'BL' bilinear softening or 'exponential'."));
  s.key(real("bars.*.interface_strength_scale", 1.0, Range{0.0, 1e6, true, false}, "",
             "Multiplies sigma_n,t and tau of a nonlinear interface (NL-A, NL-B; after NL-B's "
             "halving): "
             "for studies of the bond beyond the paper's two variants."));
  s.key(real("bars.*.interface_energy_scale", 1.0, Range{0.0, 1e6, true, false}, "",
             "Multiplies G_fn and G_fs of a nonlinear interface (NL-A, NL-B)."));
  s.key(real("bars.*.pull_velocity", 0.0, Range{0.0, 1e3}, "m/s",
             "Pull-out: the bar's first cylinder (at 'start') is moved at this speed along end -> "
             "start, its rotation held (0 = not pulled)."));
  s.key(real("bars.*.pull_ramp_time", 0.0, Range{0.0, 1e3}, "s",
             "The pull speed rises smoothly from 0 over this time."));
  s.key(real("bars.*.sphere_spacing", 0.0, Range{0.0, 10.0}, "m",
             "Spacing of the interface spheres along each cylinder; 0 = D / 2."));

  s.section("output", "What is written and how.");
  s.key(typed("output.history_rows", KeyType::Integer, std::int64_t{2000}, Range{10.0, 1.0e7},
              "About this many rows of history.csv over the run."));
  s.key(typed("output.snapshots", KeyType::Integer, std::int64_t{10}, Range{0.0, 1.0e5},
              "About this many VTU snapshots over the run (plus the first and the last)."));
  s.key(choice("output.vtu_encoding", std::string("binary"), {"binary", "ascii"},
               "VTU data encoding: 'binary' (base64, compact) or 'ascii' (readable)."));
  s.key(typed("output.write_facets", KeyType::Boolean, true, Range{},
              "Write facets.vtu (the contact facets as polygons)."));
}

Schema build() {
  Schema s;
  declare_specimen_and_generation(s);
  declare_contact_and_solver(s);
  declare_plates_loading_and_stop(s);
  declare_bars_and_output(s);
  return s;
}

}  // namespace

const Schema& scenario_schema() {
  static const Schema schema = build();
  return schema;
}

}  // namespace rcdem::config
