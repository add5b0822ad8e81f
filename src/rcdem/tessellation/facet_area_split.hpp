#pragma once
// The local contact points of one Voronoi facet (paper Figure 1) and their areas, SPEC (S1):
// the facet is fan-triangulated from its area centroid ("gravity centre"); each triangle
// (c, v_i, v_i+1) gives a third of its area to each corner. The centroid gets A/3 and each
// vertex a third of its two adjacent triangles, so the areas sum to the facet area A.
#include <span>
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem {

struct FacetSplit {
  Vec3 centroid = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  // unit normal by the vertices' orientation (Newell)
  Real area = 0.0;
  Real centroid_area = 0.0;
  std::vector<Real> vertex_area;  // one per vertex, in the given order
};

// Vertices of a planar convex polygon in order (either orientation).
FacetSplit split_facet_area(std::span<const Vec3> vertices);

// Drops vertices closer than `tolerance` to their predecessor (voro++ can return near-duplicate
// vertices where a cell edge is almost degenerate; they would be local points with no area).
std::vector<Vec3> merge_close_vertices(std::span<const Vec3> vertices, Real tolerance);

}  // namespace rcdem
