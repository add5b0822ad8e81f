#pragma once
// The VGCM-3D contact network (paper 2.1-2.2) as a structure of arrays. A contact is a Voronoi
// facet shared by two particles; its local points are stored contiguously, the facet centroid
// first and then the facet vertices in polygon order, so the facet polygon is points
// [point_begin[c] + 1, point_begin[c + 1]) and nothing is stored twice.
#include <vector>

#include "rcdem/contact/laws/local_point_state.hpp"
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
  std::vector<LocalPointConstants> constants;  // kn, ks, fn_max, c_max: read together per point

  Index contact_count() const { return static_cast<Index>(particle_a.size()); }
  Index point_count() const { return static_cast<Index>(point_area.size()); }
  Index points_of(Index c) const { return point_begin[c + 1] - point_begin[c]; }
};

// The steel-concrete interface of one bar (paper 2.6, SPEC 8): one contact per concrete particle,
// between that particle (particle_a, a body) and the cylinder carrying the nearest interface
// sphere (particle_b, the cylinder's body index). anchor0 is that sphere's centre at t = 0: the
// contact normal is taken perpendicular to the cylinder's axis through it.
struct InterfaceContacts {
  int bar = 0;
  ContactNetwork net;
  std::vector<Vec3> anchor0;
};

// The faces of the particles' Voronoi cells that lie on the specimen's outer faces (the cells are
// clipped by them). Rigid plates act on the particles through these faces (SPEC 6).
struct BoundaryFaces {
  std::vector<Index> particle;
  std::vector<int> face;  // 0..5 = x-, x+, y-, y+, z-, z+
  std::vector<Real> area;
  std::vector<Vec3> centroid;  // on the specimen face, at t = 0
  Index size() const { return static_cast<Index>(particle.size()); }
};

}  // namespace rcdem
