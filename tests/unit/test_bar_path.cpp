// A bent bar's centreline (config/bar_path.hpp, issue 41 item 4): corners rounded by tangent arcs
// of the bend radius, cut into chords of at most the given turn; a loop closes on itself.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rcdem/config/bar_path.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/reinforcement/bar_builder.hpp"

using namespace rcdem;

// A square rounded at its corners with half its side is a circle: every point at R from the
// centre, 4 x 3 chords of 30 degrees.
TEST(BarPath, ASquareRoundedByHalfItsSideIsACircle) {
  const Real R = 0.05;
  const std::vector<Vec3> corners = {Vec3(-R, -R, 0), Vec3(R, -R, 0), Vec3(R, R, 0),
                                     Vec3(-R, R, 0)};
  const std::vector<Vec3> line = bar_centreline(corners, true, R, "test");
  ASSERT_EQ(line.size(), 12U);
  for (const Vec3& p : line) EXPECT_NEAR(p.norm(), R, 1e-15);
  for (std::size_t i = 0; i < line.size(); ++i)
    EXPECT_NEAR((line[(i + 1) % line.size()] - line[i]).norm(), 2 * R * std::sin(kPi / 12), 1e-15);
}

// An open L: straight to the bend's tangent point, the arc tangent to both legs, straight on.
TEST(BarPath, AnOpenBendIsTangentToBothLegs) {
  const Real r = 0.02;
  const std::vector<Vec3> line =
      bar_centreline({Vec3(0, 0, 0), Vec3(0.3, 0, 0), Vec3(0.3, 0.2, 0)}, false, r, "test");
  ASSERT_EQ(line.size(), 6U);  // start, 4 arc points (3 chords of 30 degrees), end
  EXPECT_EQ(line.front(), Vec3(0, 0, 0));
  EXPECT_EQ(line.back(), Vec3(0.3, 0.2, 0));
  EXPECT_NEAR((line[1] - Vec3(0.3 - r, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((line[4] - Vec3(0.3, r, 0)).norm(), 0.0, 1e-15);
  for (std::size_t i = 1; i <= 4; ++i)
    EXPECT_NEAR((line[i] - Vec3(0.3 - r, r, 0)).norm(), r, 1e-15);
  // The bar along it: a cylinder per chord or more, a node at every junction.
  const Bar bar = build_polyline_bar(line, false, 0.008, SteelMaterial{200e9, 0.3, 5e8, 7850},
                                     0.032);
  EXPECT_EQ(bar.nodes.size(), bar.cylinders.size() - 1);
  const Bar loop = build_polyline_bar(
      bar_centreline({Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.1, 0.1, 0), Vec3(0, 0.1, 0)}, true,
                     0.02, "test"),
      true, 0.008, SteelMaterial{200e9, 0.3, 5e8, 7850}, 0.032);
  EXPECT_EQ(loop.nodes.size(), loop.cylinders.size());
  EXPECT_EQ(loop.nodes.back()[1], 0);
}

TEST(BarPath, RefusesABendThatDoesNotFitAndCoincidentPoints) {
  EXPECT_THROW(bar_centreline({Vec3(0, 0, 0), Vec3(0.03, 0, 0), Vec3(0.03, 0.2, 0)}, false, 0.02,
                              "test"),
               Error);
  EXPECT_THROW(bar_centreline({Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0.03, 0.2, 0)}, false, 0.01,
                              "test"),
               Error);
  EXPECT_THROW(bar_centreline({Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0, 0)}, false, 0.01,
                              "test"),
               Error);
}
