#include <gtest/gtest.h>

#include <sstream>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/schema.hpp"
#include "rcdem/core/error.hpp"
#include "small_scenarios.hpp"

using namespace rcdem;

namespace {

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "bad.toml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Scenario, DefaultsAreTable2) {
  const Scenario s = test::small_box();
  EXPECT_DOUBLE_EQ(s.contact.E_bar, 48.7e9);
  EXPECT_DOUBLE_EQ(s.contact.alpha, 0.3);
  EXPECT_DOUBLE_EQ(s.contact.sigma_nt, 4.15e6);
  EXPECT_DOUBLE_EQ(s.contact.G_fs, 2380.785);
  EXPECT_DOUBLE_EQ(s.generation.aggregate_content, 568.5);
  EXPECT_DOUBLE_EQ(s.generation.porosity, 0.10);
  EXPECT_EQ(s.specimen.size, Vec3(0.06, 0.05, 0.04));
}

TEST(Scenario, UnknownKeyNamesFileLineAndKnownKeys) {
  const std::string msg = error_of("[specimen]\nshape = \"box\"\nsize = [0.1,0.1,0.1]\nsiz = 3\n");
  EXPECT_NE(msg.find("bad.toml:4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown key 'specimen.siz'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("size"), std::string::npos) << msg;
}

TEST(Scenario, WrongTypeAndRangeSayWhatWasExpected) {
  std::string msg = error_of(test::small_box_text(1, "voronoi", "[contact]\nalpha = \"x\"\n"));
  EXPECT_NE(msg.find("contact.alpha"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a number"), std::string::npos) << msg;
  msg = error_of(test::small_box_text(1, "voronoi", "[contact]\nE_bar = -1.0\n"));
  EXPECT_NE(msg.find("in [1000, 1e+13]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("got -1"), std::string::npos) << msg;
}

TEST(Scenario, MissingRequiredKey) {
  const std::string msg = error_of("[specimen]\nshape = \"box\"\n");
  EXPECT_NE(msg.find("missing required key 'specimen.size'"), std::string::npos) << msg;
}

TEST(Scenario, CrossKeyChecks) {
  EXPECT_NE(error_of(test::small_box_text(1, "voronoi", "[generation.aggregate]\nd_min = 0.013\n"))
                .find("must not exceed"),
            std::string::npos);
  EXPECT_NE(
      error_of(test::small_box_text(1, "voronoi", "[generation.aggregate]\ncontent = 2500.0\n"))
          .find("cannot fit"),
      std::string::npos);
}

TEST(Schema, TemplateParsesBackWithEveryDefault) {
  // print-schema's template, with the required keys filled in, is itself a valid scenario.
  std::ostringstream out;
  config::scenario_schema().print_template(out);
  std::string text = out.str();
  const auto fill = [&](const std::string& from, const std::string& to) {
    const auto pos = text.find(from);
    ASSERT_NE(pos, std::string::npos);
    text.replace(pos, from.size(), to);
  };
  fill("# shape = ...   # required", "shape = \"box\"");
  fill("# size = ...   # required", "size = [0.1, 0.1, 0.1]");
  const Scenario s = parse_scenario(text, "template.toml");
  EXPECT_EQ(s.generation.relaxation_iterations, 300);
  EXPECT_DOUBLE_EQ(s.contact.G_fn, 9.002);
}

// A key's default is its member's initialiser (config/scenario_schema.cpp binds the two), so what
// a file that omits the key gets and what code that builds a Scenario gets are one value. This
// test checks the round trip, default -> file -> member, field by field: a scenario of only the
// required keys, one plate and one bar (its yield stress is required) against default-constructed
// structs. The solver keys solver.preset governs are the exception: SolverSettings{} is preset
// "basic", so that file names it (the default preset is SolverPreset's test below).
constexpr const char* kOnlyRequiredKeys =
    "[specimen]\nshape = \"beam\"\nsize = [0.4, 0.1, 0.1]\n"
    "[plates.p]\nface = \"z+\"\n[loading]\ncontrol_plate = \"p\"\n[stop]\nsteps = 1\n"
    "[bars.b]\nstart = [0.05, 0.05, 0.02]\nend = [0.35, 0.05, 0.02]\ndiameter = 0.008\n"
    "f_y = 5e8\n";

TEST(Scenario, SchemaDefaultsEqualTheStructsDefaults) {
  const Scenario s = parse_scenario(std::string(kOnlyRequiredKeys) + "[solver]\npreset = \"basic\"\n",
                                    "defaults.toml");
  const GenerationSettings g;
  EXPECT_EQ(s.generation.seed, g.seed);
  EXPECT_EQ(s.generation.porosity, g.porosity);
  EXPECT_EQ(s.generation.relaxation_iterations, g.relaxation_iterations);
  EXPECT_EQ(s.generation.min_distance_factor, g.min_distance_factor);
  EXPECT_EQ(s.generation.max_particles, g.max_particles);
  EXPECT_EQ(s.generation.aggregate_content, g.aggregate_content);
  EXPECT_EQ(s.generation.aggregate_density, g.aggregate_density);
  EXPECT_EQ(s.generation.aggregate_d_min, g.aggregate_d_min);
  EXPECT_EQ(s.generation.aggregate_d_max, g.aggregate_d_max);
  EXPECT_EQ(s.generation.aggregate_grading, g.aggregate_grading);
  EXPECT_EQ(s.generation.fuller_exponent, g.fuller_exponent);
  EXPECT_EQ(s.generation.mortar_d_min, g.mortar_d_min);
  EXPECT_EQ(s.generation.mortar_d_max, g.mortar_d_max);
  const Scenario d;
  EXPECT_EQ(s.tessellation, d.tessellation);
  EXPECT_EQ(s.law, d.law);
  const ContactParameters c;
  EXPECT_EQ(s.contact.E_bar, c.E_bar);
  EXPECT_EQ(s.contact.alpha, c.alpha);
  EXPECT_EQ(s.contact.mu_c, c.mu_c);
  EXPECT_EQ(s.contact.sigma_nt, c.sigma_nt);
  EXPECT_EQ(s.contact.tau, c.tau);
  EXPECT_EQ(s.contact.G_fn, c.G_fn);
  EXPECT_EQ(s.contact.G_fs, c.G_fs);
  const SolverSettings v;
  EXPECT_EQ(s.solver.density, v.density);
  EXPECT_EQ(s.solver.estimate, v.estimate);
  EXPECT_EQ(s.solver.dt_safety, v.dt_safety);
  EXPECT_EQ(s.solver.time_step, v.time_step);
  EXPECT_EQ(s.solver.damping, v.damping);
  EXPECT_EQ(s.solver.mass_scaling, v.mass_scaling);
  EXPECT_EQ(s.solver.added_mass_limit, v.added_mass_limit);
  EXPECT_EQ(s.solver.bar_rotational_inertia_scaling, v.bar_rotational_inertia_scaling);
  EXPECT_EQ(s.solver.particle_rotational_inertia_scaling, v.particle_rotational_inertia_scaling);
  EXPECT_EQ(s.solver.condense_elastic_contacts, v.condense_elastic_contacts);
  const LoadingRateSettings l;
  EXPECT_EQ(s.loading_rate.adaptive, l.adaptive);
  EXPECT_EQ(s.loading_rate.max_factor, l.max_factor);
  EXPECT_EQ(s.loading_rate.kinetic_ratio, l.kinetic_ratio);
  EXPECT_EQ(s.loading_rate.damage_work_ratio, l.damage_work_ratio);
  EXPECT_EQ(s.loading_rate.doubling_time, l.doubling_time);
  const StopSettings t;
  EXPECT_EQ(s.stop.displacement, t.displacement);
  EXPECT_EQ(s.stop.load_drop, t.load_drop);
  EXPECT_EQ(s.stop.post_peak_displacement, t.post_peak_displacement);
  EXPECT_EQ(s.stop.time, t.time);
  const OutputSettings o;
  EXPECT_EQ(s.output.binary_vtu, o.binary_vtu);
  EXPECT_EQ(s.output.write_facets, o.write_facets);
  EXPECT_EQ(s.output.history_rows, o.history_rows);
  EXPECT_EQ(s.output.snapshots, o.snapshots);
  const PlateSettings p;
  ASSERT_EQ(s.plates.size(), 1u);
  EXPECT_EQ(s.plates[0].extent, p.extent);
  EXPECT_EQ(s.plates[0].velocity, p.velocity);
  EXPECT_EQ(s.plates[0].ramp_time, p.ramp_time);
  EXPECT_EQ(s.plates[0].glued, p.glued);
  EXPECT_EQ(s.plates[0].friction, p.friction);
  const BarSettings b;
  ASSERT_EQ(s.bars.size(), 1u);
  EXPECT_EQ(s.bars[0].cylinder_length, b.cylinder_length);
  EXPECT_EQ(s.bars[0].E, b.E);
  EXPECT_EQ(s.bars[0].nu, b.nu);
  EXPECT_EQ(s.bars[0].density, b.density);
  EXPECT_EQ(s.bars[0].interface, b.interface);
  EXPECT_EQ(s.bars[0].interface_softening, b.interface_softening);
  EXPECT_EQ(s.bars[0].interface_strength_scale, b.interface_strength_scale);
  EXPECT_EQ(s.bars[0].interface_energy_scale, b.interface_energy_scale);
  EXPECT_EQ(s.bars[0].sphere_spacing, b.sphere_spacing);
  EXPECT_EQ(s.bars[0].pull_velocity, b.pull_velocity);
  EXPECT_EQ(s.bars[0].pull_ramp_time, b.pull_ramp_time);
  EXPECT_EQ(s.specimen.notch_depth, SpecimenSettings{}.notch_depth);
  EXPECT_EQ(s.specimen.notch_width, SpecimenSettings{}.notch_width);
}

// solver.preset (docs/model.md 6): a file that leaves the solver alone gets the study's
// quasi-static set-up, print-schema shows it, a key the file sets wins over the preset, and
// dt_safety follows the estimate so that naming per_body alone stays valid.
TEST(SolverPreset, AFileWithoutSolverKeysGetsTheQuasiStaticSetUp) {
  const Scenario s = parse_scenario(kOnlyRequiredKeys, "defaults.toml");
  EXPECT_EQ(s.solver.estimate, TimeStepEstimate::Assembled);
  EXPECT_EQ(s.solver.dt_safety, 0.7);
  EXPECT_EQ(s.solver.damping, 0.3);
  EXPECT_EQ(s.solver.particle_rotational_inertia_scaling, 2.5);
  EXPECT_EQ(s.solver.bar_rotational_inertia_scaling, 30.0);
  // The same as the template print-schema writes, which names every default.
  std::ostringstream out;
  config::scenario_schema().print_template(out);
  const std::string t = out.str();
  for (const char* line : {"preset = \"quasi_static\"\n", "time_step_estimate = \"assembled\"\n",
                           "dt_safety = 0.7\n", "damping = 0.3\n",
                           "particle_rotational_inertia_scaling = 2.5\n",
                           "bar_rotational_inertia_scaling = 30.0\n"})
    EXPECT_NE(t.find(std::string("\n") + line), std::string::npos) << line;
}

TEST(SolverPreset, KeysTheFileSetsWinAndDtSafetyFollowsTheEstimate) {
  const auto with = [](const std::string& solver) {
    return parse_scenario(std::string(kOnlyRequiredKeys) + "[solver]\n" + solver, "p.toml");
  };
  const Scenario a = with("damping = 0.5\n");
  EXPECT_EQ(a.solver.damping, 0.5);
  EXPECT_EQ(a.solver.estimate, TimeStepEstimate::Assembled);
  EXPECT_EQ(a.solver.particle_rotational_inertia_scaling, 2.5);
  const Scenario b = with("time_step_estimate = \"per_body\"\n");
  EXPECT_EQ(b.solver.dt_safety, 0.3);
  EXPECT_EQ(b.solver.damping, 0.3);
  const Scenario c = with("preset = \"basic\"\nbar_rotational_inertia_scaling = 10\n");
  EXPECT_EQ(c.solver.estimate, TimeStepEstimate::PerBody);
  EXPECT_EQ(c.solver.dt_safety, 0.3);
  EXPECT_EQ(c.solver.damping, 0.7);
  EXPECT_EQ(c.solver.particle_rotational_inertia_scaling, 1.0);
  EXPECT_EQ(c.solver.bar_rotational_inertia_scaling, 10.0);
  const Scenario d = with("preset = \"basic\"\ntime_step_estimate = \"assembled\"\n");
  EXPECT_EQ(d.solver.dt_safety, 0.3);  // basic keeps SPEC 6's 0.3 on either estimate
}

TEST(SolverPreset, ErrorsNameThePresetOrTheLine) {
  std::string msg = error_of(std::string(kOnlyRequiredKeys) + "[solver]\npreset = \"fast\"\n");
  EXPECT_NE(msg.find("bad.toml:16: key 'solver.preset'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("\"quasi_static\", \"basic\""), std::string::npos) << msg;
  // A dt_safety the preset would take with the other estimate is refused with the file's line.
  msg = error_of(std::string(kOnlyRequiredKeys) +
                 "[solver]\ntime_step_estimate = \"per_body\"\ndt_safety = 0.7\n");
  EXPECT_NE(msg.find("bad.toml:17: key 'solver.dt_safety' = 0.7"), std::string::npos) << msg;
}
