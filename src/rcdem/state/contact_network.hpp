#pragma once
// The VGCM-3D contact network (paper 2.1-2.2) as a structure of arrays. A contact is a Voronoi
// facet shared by two particles; its local points are stored contiguously, the facet centroid
// first and then the facet vertices in polygon order, so the facet polygon is points
// [point_begin[c] + 1, point_begin[c + 1]) and nothing is stored twice.
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem {

struct ContactNetwork {
  // Per contact.
  std::vector<Index> particle_a, particle_b;  // a < b
  std::vector<Real> distance0;                // d in (3): centre distance at t = 0
  std::vector<Real> facet_area;               // A, the facet's area
  std::vector<Index> point_begin;             // CSR offsets, size contacts + 1

  // Per local point (paper Figure 1): its position at t = 0, its share of the facet area (S1) and
  // its stiffness (3)-(4) and strength (5)-(6).
  std::vector<Vec3> point_position0;
  std::vector<Real> point_area;
  std::vector<Real> kn, ks, fn_max, c_max;

  Index contact_count() const { return static_cast<Index>(particle_a.size()); }
  Index point_count() const { return static_cast<Index>(point_area.size()); }
  Index points_of(Index c) const { return point_begin[c + 1] - point_begin[c]; }
};

}  // namespace rcdem
