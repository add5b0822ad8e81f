// What a test measures (solver/test_measures.hpp, issue 41): a gauge reads any affine motion of
// the material exactly (uniform strain, rigid motion), relative to plates as declared; the load
// over several plates is their reactions' sum and the displacement their mean.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/scenario_text.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/solver/test_measures.hpp"
#include "rcdem/specimens/specimen.hpp"

using namespace rcdem;

namespace {

// The four-point beam of examples/four_point_bending/plain.toml with the gauges given (and
// none as the displacement).
Scenario four_point(const std::string& gauges) {
  const std::filesystem::path file =
      std::filesystem::path(RCDEM_SOURCE_DIR) / "examples/four_point_bending/plain.toml";
  std::string text = config::read_scenario_file(file, "scenario");
  text = text.substr(0, text.find("[gauges.midspan]")) + gauges + R"(
[stop]
steps = 10
)";
  const std::string displacement_gauge = "displacement_gauge = \"midspan\"";
  text.erase(text.find(displacement_gauge), displacement_gauge.size());
  return parse_scenario(text, file.string());
}

const char* kGauges = R"(
[gauges.fit]
point = [0.33, 0.07, 0.04]
direction = "x"
radius = 0.03
[gauges.nearest]
point = [0.33, 0.07, 0.04]
direction = "y"
relative_to = []
[gauges.deflection]
point = [0.35, 0.075, 0.05]
relative_to = ["support_left", "support_right"]
radius = 0.025
[gauges.opening]
kind = "opening"
point = [0.25, 0.075, 0.01]
to = [0.45, 0.08, 0.02]
radius = 0.02
[gauges.opening_z]
kind = "opening"
point = [0.25, 0.075, 0.01]
to = [0.45, 0.08, 0.02]
direction = "z"
radius = 0.02
)";

// x = x0 + g (x0 - c) + t for every body, orientations `q`.
void move_affinely(Bodies& b, const Eigen::Matrix3d& g, const Vec3& c, const Vec3& t,
                   const Quat& q) {
  for (Index i = 0; i < b.size(); ++i) {
    b.position[i] = b.position0[i] + g * (b.position0[i] - c) + t;
    b.orientation[i] = q;
  }
}

const Gauge& gauge(const TestMeasures& m, const std::string& name) {
  for (const Gauge& g : m.gauges())
    if (g.name() == name) return g;
  throw std::runtime_error("no gauge " + name);
}

}  // namespace

// A uniform strain with a translation: the fitted gauges read the field at their points exactly;
// the opening is the field's difference along the line (or an axis).
TEST(TestMeasures, GaugesReadAUniformStrainExactly) {
  const Scenario sc = four_point(kGauges);
  Simulation sim(sc, build_specimen(sc));
  const TestMeasures m(sim, sc);
  Eigen::Matrix3d g;
  g << 2e-4, 3e-5, -1e-5, 5e-5, -1.5e-4, 2e-5, -4e-5, 1e-5, 3e-4;
  const Vec3 c(0.3, -0.2, 0.1), t(1e-5, -2e-5, 3e-5);
  move_affinely(sim.bodies(), g, c, t, Quat::Identity());
  const auto field = [&](const Vec3& p) { return Vec3(g * (p - c) + t); };
  const Vec3 p(0.33, 0.07, 0.04);
  EXPECT_NEAR(gauge(m, "fit").value(sim), field(p).x(), 1e-15);
  const Vec3 a(0.25, 0.075, 0.01), b(0.45, 0.08, 0.02);
  const Vec3 along = (b - a).normalized();
  EXPECT_NEAR(gauge(m, "opening").value(sim), (field(b) - field(a)).dot(along), 1e-15);
  EXPECT_NEAR(gauge(m, "opening_z").value(sim), (field(b) - field(a)).z(), 1e-15);
  // The plates have not moved: the deflection is the field's z at its point.
  EXPECT_NEAR(gauge(m, "deflection").value(sim), field(Vec3(0.35, 0.075, 0.05)).z(), 1e-15);
  // The nearest particle carries the point rigidly: under a strain it reads the field at its own
  // centre, off by the strain times the distance (a particle radius at most).
  EXPECT_NEAR(gauge(m, "nearest").value(sim), field(p).y(), 3e-4 * 0.012);
}

// A finite rigid rotation with a translation: every gauge reads it exactly, the nearest-particle
// one through the particle's rotation, the fitted ones as an affine field.
TEST(TestMeasures, GaugesReadARigidMotionExactly) {
  const Scenario sc = four_point(kGauges);
  Simulation sim(sc, build_specimen(sc));
  const TestMeasures m(sim, sc);
  const Quat q(Eigen::AngleAxisd(0.02, Vec3(0.3, -1.0, 0.5).normalized()));
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const Vec3 c(0.35, 0.075, 0.05), t(2e-4, -1e-4, 5e-5);
  move_affinely(sim.bodies(), r - Eigen::Matrix3d::Identity(), c, t, q);
  const auto u = [&](const Vec3& p) { return Vec3((r - Eigen::Matrix3d::Identity()) * (p - c) + t); };
  const Vec3 p(0.33, 0.07, 0.04);
  EXPECT_NEAR(gauge(m, "nearest").value(sim), u(p).y(), 1e-16);
  EXPECT_NEAR(gauge(m, "fit").value(sim), u(p).x(), 1e-15);
  // A rigid motion opens nothing along the line (to the rotation's second order).
  const Vec3 a(0.25, 0.075, 0.01), b(0.45, 0.08, 0.02);
  EXPECT_NEAR(gauge(m, "opening").value(sim), (u(b) - u(a)).dot((b - a).normalized()), 1e-15);
  EXPECT_LT(std::abs(gauge(m, "opening").value(sim)), 0.5 * 0.02 * 0.02 * (b - a).norm());
}

// Relative to plates: the plates' mean displacement along the gauge is taken off; the load over
// two plates is the sum of their loads and the control's displacement their mean.
TEST(TestMeasures, RelativeToPlatesAndTheLoadOverTwoPlates) {
  const Scenario sc = four_point(kGauges);
  Simulation sim(sc, build_specimen(sc));
  const TestMeasures m(sim, sc);
  const Vec3 t(0.0, 0.0, -3e-4);
  move_affinely(sim.bodies(), Eigen::Matrix3d::Zero(), Vec3::Zero(), t, Quat::Identity());
  std::vector<Plate>& plates = sim.plates();
  const auto plate = [&](const std::string& name) -> Plate& {
    for (Plate& p : plates)
      if (p.name == name) return p;
    throw std::runtime_error(name);
  };
  plate("support_left").displacement = -1e-4;
  plate("support_right").displacement = -2e-4;
  EXPECT_NEAR(gauge(m, "deflection").value(sim), -3e-4 - (-1.5e-4), 1e-18);
  plate("load_left").force = Vec3(0.0, 0.0, 1200.0);
  plate("load_right").force = Vec3(0.0, 0.0, 800.0);
  plate("load_left").displacement = -1e-4;
  plate("load_right").displacement = -3e-4;
  // A plate moving down (velocity < 0) carries load as the specimen pushes it up (+z).
  EXPECT_DOUBLE_EQ(m.load(), 2000.0);
  EXPECT_DOUBLE_EQ(m.control_displacement(), -2e-4);
  EXPECT_TRUE(m.several_plates());
}
