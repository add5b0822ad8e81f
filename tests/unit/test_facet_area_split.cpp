#include <gtest/gtest.h>

#include <vector>

#include "rcdem/tessellation/facet_area_split.hpp"

using namespace rcdem;

TEST(FacetAreaSplit, SquareGivesThirdToCentroidAndSixthToEachCorner) {
  const std::vector<Vec3> sq = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  const FacetSplit s = split_facet_area(sq);
  EXPECT_NEAR(s.area, 4.0, 1e-14);
  EXPECT_NEAR((s.centroid - Vec3(1, 1, 0)).norm(), 0.0, 1e-14);
  EXPECT_NEAR(s.centroid_area, 4.0 / 3.0, 1e-14);
  for (Real a : s.vertex_area) EXPECT_NEAR(a, 4.0 / 6.0, 1e-14);
}

TEST(FacetAreaSplit, IrregularPolygonCentroidAndSum) {
  // A right triangle: area centroid at the vertex mean; the fan triangles from it each have A/3.
  const std::vector<Vec3> tri = {{0, 0, 1}, {3, 0, 1}, {0, 6, 1}};
  const FacetSplit s = split_facet_area(tri);
  EXPECT_NEAR(s.area, 9.0, 1e-13);
  EXPECT_NEAR((s.centroid - Vec3(1, 2, 1)).norm(), 0.0, 1e-13);
  EXPECT_NEAR(s.centroid_area, 3.0, 1e-13);
  for (Real a : s.vertex_area) EXPECT_NEAR(a, 2.0, 1e-13);

  // A skewed pentagon, tilted in space, traversed clockwise: the sum is the area either way.
  std::vector<Vec3> pent = {{0, 0, 0}, {4, 0, 1}, {5, 3, 2}, {2, 5, 2}, {-1, 2, 0.5}};
  const Vec3 n = (pent[1] - pent[0]).cross(pent[4] - pent[0]).normalized();
  // Project onto the plane through pent[0] so that the polygon is planar.
  for (auto& p : pent) p -= (p - pent[0]).dot(n) * n;
  const FacetSplit a = split_facet_area(pent);
  std::reverse(pent.begin(), pent.end());
  const FacetSplit b = split_facet_area(pent);
  Real sum = a.centroid_area;
  for (Real v : a.vertex_area) sum += v;
  EXPECT_NEAR(sum / a.area, 1.0, 1e-14);
  EXPECT_NEAR(a.area / b.area, 1.0, 1e-14);
  EXPECT_NEAR((a.centroid - b.centroid).norm(), 0.0, 1e-12);
}

TEST(FacetAreaSplit, MergesNearDuplicateVertices) {
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {1 + 1e-12, 0, 0},
                               {1, 1, 0}, {0, 1, 0}, {1e-13, 0, 0}};
  EXPECT_EQ(merge_close_vertices(v, 1e-9).size(), 4u);
}
