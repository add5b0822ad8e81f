// Ties where two bars touch (reinforcement/bar_ties.hpp, issue 41 item 4): where they form, and
// the tie node's springs against the thinner bar's (9), its rigid-motion invariance and balance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rcdem/config/bar_path.hpp"
#include "rcdem/reinforcement/bar_ties.hpp"

using namespace rcdem;

namespace {

const SteelMaterial kSteel{200e9, 0.3, 5e8, 7850};
constexpr Real kBarD = 0.008, kStirrupD = 0.004;

// A longitudinal bar along x at (y, z).
Bar longitudinal(Real y, Real z) {
  return build_straight_bar(Vec3(0.0, y, z), Vec3(0.3, y, z), kBarD, kSteel, 0.032);
}

// A closed stirrup in the plane x = 0.15 round bars at y = 0.04 and 0.11, z = 0.02: its legs
// `clear` beyond touching (0: touching, the bends concentric with the bars).
Bar stirrup(Real clear) {
  const Real r = 0.5 * (kBarD + kStirrupD) + clear;  // the bend radius of the stirrup's axis
  const Real y0 = 0.04 - r, y1 = 0.11 + r, z0 = 0.02 - r, z1 = 0.09;
  const std::vector<Vec3> corners = {Vec3(0.15, y0, z0), Vec3(0.15, y1, z0), Vec3(0.15, y1, z1),
                                     Vec3(0.15, y0, z1)};
  return build_polyline_bar(bar_centreline(corners, true, r, "stirrup"), true, kStirrupD, kSteel,
                            0.016);
}

Quat rotation(const Vec3& axis, Real angle) {
  return Quat(Eigen::AngleAxis<Real>(angle, axis.normalized()));
}

}  // namespace

// A stirrup whose bends wrap the two bars is tied once at each: at the middle of the bend, where
// the two axes are the sum of the radii apart along the bend's bisector.
TEST(BarTies, AStirrupIsTiedOnceAtEachBarItWraps) {
  const std::vector<Bar> bars = {longitudinal(0.04, 0.02), longitudinal(0.11, 0.02), stirrup(0.0)};
  const std::vector<BarTie> ties = find_bar_ties(bars);
  ASSERT_EQ(ties.size(), 2U);
  const Real radii = 0.5 * (kBarD + kStirrupD);
  for (std::size_t k = 0; k < 2; ++k) {
    const BarTie& t = ties[k];
    EXPECT_EQ(t.bar_a, static_cast<int>(k));
    EXPECT_EQ(t.bar_b, 2);
    const Vec3 bar_axis(0.15, k == 0 ? 0.04 : 0.11, 0.02);
    EXPECT_NEAR((t.point_a - bar_axis).norm(), 0.0, 1e-12);  // on the bar's axis, at the stirrup
    const Real d = (t.point_b - t.point_a).norm();
    EXPECT_NEAR(d, radii, bar_touch_tolerance(kBarD, kStirrupD));
    // The bend's middle chord: its closest point lies on the bisector, 45 degrees down and out.
    const Vec3 out = (t.point_b - t.point_a) / d;
    const Real side = k == 0 ? -1.0 : 1.0;
    EXPECT_NEAR(out.dot(Vec3(0.0, side, -1.0).normalized()), 1.0, 1e-12);
  }
}

// Bars that pass clear of each other, or parallel bars side by side, are not tied; two bars
// crossing at right angles in contact are tied once, at the crossing.
TEST(BarTies, OnlyTouchingBarsAreTied) {
  EXPECT_TRUE(find_bar_ties({longitudinal(0.04, 0.02), longitudinal(0.11, 0.02), stirrup(0.002)})
                  .empty());
  EXPECT_TRUE(find_bar_ties({longitudinal(0.04, 0.02), longitudinal(0.06, 0.02)}).empty());
  const Real radii = kBarD;
  const Bar across =
      build_straight_bar(Vec3(0.1, 0.0, 0.02 + radii), Vec3(0.1, 0.2, 0.02 + radii), kBarD, kSteel);
  const std::vector<BarTie> ties = find_bar_ties({longitudinal(0.04, 0.02), across});
  ASSERT_EQ(ties.size(), 1U);
  EXPECT_NEAR((ties[0].point_a - Vec3(0.1, 0.04, 0.02)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((ties[0].point_b - Vec3(0.1, 0.04, 0.02 + radii)).norm(), 0.0, 1e-12);
}

// The tie node between a bar and a stirrup's bend: no force at rest or after a large rigid motion
// of the pair; separating the two axes by delta gives the thinner bar's k_a delta along the tie,
// sliding the stirrup along the bar its k_t delta across it; forces equal and opposite, moments
// balanced.
TEST(BarTies, TheTieIsTheThinnerBarsNode) {
  const std::vector<Bar> bars = {longitudinal(0.04, 0.02), longitudinal(0.11, 0.02), stirrup(0.0)};
  const BarTie tie = find_bar_ties(bars)[0];
  const InteractionNode node = make_tie_node(tie, bars, Quat::Identity(), Quat::Identity());
  const CylinderGeometry& a = bars[0].cylinders[static_cast<std::size_t>(tie.cylinder_a)];
  const CylinderGeometry& b = bars[2].cylinders[static_cast<std::size_t>(tie.cylinder_b)];
  const NodeStiffness k = node_stiffness(a.length, b.length, kStirrupD, kSteel);
  EXPECT_EQ(node.k.axial, k.axial);
  EXPECT_EQ(node.k.yield_force, k.yield_force);
  const Real f_scale = k.yield_force;

  NodeState s;
  const NodeForces rest = evaluate_node(node, s, a.centre, Quat::Identity(), b.centre,
                                        Quat::Identity());
  EXPECT_LT(rest.force_b.norm(), 1e-12 * f_scale);
  const Quat r = rotation(Vec3(0.3, -0.7, 0.2), 1.9);
  const Vec3 shift(0.2, 0.1, -0.3);
  const NodeForces moved = evaluate_node(node, s, r * a.centre + shift, r, r * b.centre + shift, r);
  EXPECT_LT(moved.force_b.norm(), 1e-12 * f_scale);
  EXPECT_LT(moved.torque_b.norm(), 1e-12 * f_scale * kBarD);

  const Vec3 n = (tie.point_b - tie.point_a).normalized();
  const Real delta = 1e-7;
  NodeState apart;
  const NodeForces pulled = evaluate_node(node, apart, a.centre, Quat::Identity(),
                                          b.centre + delta * n, Quat::Identity());
  EXPECT_NEAR(apart.axial_force, k.axial * delta, 1e-9 * k.axial * delta);
  EXPECT_LT((pulled.force_b + k.axial * delta * n).norm(), 1e-9 * k.axial * delta);
  EXPECT_LT(pulled.torque_b.norm(), 1e-9 * k.axial * delta * kBarD);  // along the line of centres

  NodeState slid;
  const NodeForces sliding = evaluate_node(node, slid, a.centre, Quat::Identity(),
                                           b.centre + delta * a.axis, Quat::Identity());
  EXPECT_NEAR(slid.shear_force.norm(), k.shear * delta, 1e-9 * k.shear * delta);
  EXPECT_NEAR(slid.axial_force, 0.0, 1e-9 * k.shear * delta);
  EXPECT_LT((sliding.force_b + k.shear * delta * a.axis).norm(), 1e-9 * k.shear * delta);
  EXPECT_LT((sliding.force_a + sliding.force_b).norm(), 1e-15 * f_scale);
  const Vec3 balance = sliding.torque_a + sliding.torque_b + a.centre.cross(sliding.force_a) +
                       (b.centre + delta * a.axis).cross(sliding.force_b);
  EXPECT_LT(balance.norm(), 1e-12 * k.shear * delta);
}
