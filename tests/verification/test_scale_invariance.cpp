// The model's one length scale (docs/model.md 7, "The quick resolution"): a specimen with every
// length k times larger, particles included, loaded k times more slowly, is the same test in
// units scaled by k, except for the contacts' fracture energies (a displacement times a stress).
// With G_f,n and G_f,s also scaled by k the cube reads the same E, nu and strength; with them
// unscaled it is more brittle. This is why a coarser resolution needs its own calibration and
// why its contacts carry fracture energies about k times larger.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "rcdem/calibration/uniaxial.hpp"
#include "rcdem/config/scenario.hpp"

using namespace rcdem;

namespace {

namespace fs = std::filesystem;

Scenario calibrated_cube() {
  return load_scenario(fs::path(RCDEM_SOURCE_DIR) / "examples/uniaxial/cube160_calibrated.toml");
}

// The cube k times larger with particles k times coarser and, if `scale_energies`, both fracture
// energies k times larger.
Scenario scaled(Scenario s, Real k, bool scale_energies) {
  auto& g = s.generation;
  g.aggregate_d_min *= k;
  g.aggregate_d_max *= k;
  g.mortar_d_min *= k;
  g.mortar_d_max *= k;
  if (scale_energies) {
    s.contact.G_fn *= k;
    s.contact.G_fs *= k;
  }
  return s;
}

UniaxialResult tension(const Scenario& base, Real side, Real rate_factor, const std::string& tag) {
  UniaxialOptions o;
  o.size = side;
  o.rate_factor = rate_factor;
  o.stop_after_peak = 0.85;
  o.snapshots = 0;
  const fs::path dir = fs::temp_directory_path() / ("rcdem_scale_invariance_" + tag);
  fs::remove_all(dir);
  UniaxialResult r = run_uniaxial(base, UniaxialMode::Tension, o, dir);
  fs::remove_all(dir);
  return r;
}

}  // namespace

TEST(ScaleInvariance, CoarserParticlesInALargerCubeWithScaledFractureEnergiesReadTheSame) {
  const Scenario paper = calibrated_cube();
  const Real k = 2.0, side = 0.06;
  // Below the paper's 160 mm cube the calibration keeps SPEC 9's strain rate whatever the side,
  // so the larger cube is slowed by hand: its time then scales with its lengths.
  const UniaxialResult a = tension(paper, side, 1.0, "paper");
  const UniaxialResult b = tension(scaled(paper, k, true), k * side, 1.0 / k, "scaled");
  const UniaxialResult c = tension(scaled(paper, k, false), k * side, 1.0 / k, "unscaled");
  ASSERT_GT(a.strength, 1e6);
  // The same test, to the bit: with k a power of two every length, area, mass, stiffness and
  // time of the larger cube is the paper's times a power of two, exactly (the same seed gives
  // the same packing, scaled), and so are the stresses' and strains' rounding errors.
  EXPECT_EQ(b.strength, a.strength);
  EXPECT_EQ(b.E, a.E);
  EXPECT_EQ(b.nu, a.nu);
  EXPECT_EQ(b.strain_at_peak, a.strain_at_peak);
  // The same fracture energies over k times longer contacts: a more brittle concrete.
  EXPECT_LT(c.strength / a.strength, 0.9);
  std::printf("strength, E, strain at the peak scaled / paper - 1: %.2e %.2e %.2e\n",
              b.strength / a.strength - 1, b.E / a.E - 1, b.strain_at_peak / a.strain_at_peak - 1);
  std::printf(
      "tension, %.0f mm cube: %.4f MPa; %.0f mm cube, particles x%.0f: %.4f MPa with the "
      "fracture energies x%.0f, %.4f MPa without\n",
      side * 1e3, a.strength / 1e6, k * side * 1e3, k, b.strength / 1e6, k, c.strength / 1e6);
}

// The calibration slows the loading of cubes above the paper's 160 mm as their side grows, so a
// coarse resolution's cube is loaded as the paper's, scaled (uniaxial_scenario).
TEST(ScaleInvariance, CalibrationCubesAboveThePapersAreLoadedInScaledTime) {
  const Scenario paper = calibrated_cube();
  for (const UniaxialMode mode : {UniaxialMode::Compression, UniaxialMode::Tension}) {
    UniaxialOptions o;
    o.size = 0.160;
    const Scenario s160 = uniaxial_scenario(paper, mode, o);
    o.size = 0.320;
    const Scenario s320 = uniaxial_scenario(paper, mode, o);
    o.size = 0.080;
    const Scenario s80 = uniaxial_scenario(paper, mode, o);
    const auto& top = [](const Scenario& s) { return s.plates.at(1); };
    // The same plate speed (half the strain rate) and twice the ramp on the 320 mm cube; the 80
    // mm cube keeps the 160 mm cube's strain rate and ramp.
    EXPECT_DOUBLE_EQ(top(s320).velocity, top(s160).velocity);
    EXPECT_DOUBLE_EQ(top(s320).ramp_time, 2.0 * top(s160).ramp_time);
    EXPECT_DOUBLE_EQ(top(s80).velocity, 0.5 * top(s160).velocity);
    EXPECT_DOUBLE_EQ(top(s80).ramp_time, top(s160).ramp_time);
  }
}
