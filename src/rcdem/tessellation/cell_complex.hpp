#pragma once
// The Voronoi cells of all particles, each with its faces and their vertices, in flat CSR arrays.
// Kept per cell (both sides of every facet) so that tests can check facet(a,b) = facet(b,a).
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/specimen_geometry.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/state/particles.hpp"

namespace rcdem {

struct CellComplex {
  std::vector<Real> volume;       // per cell
  std::vector<Index> face_begin;  // per cell, CSR into the face arrays (size cells + 1)
  std::vector<Index>
      face_neighbour;               // per face: the particle across it, or < 0 for a specimen face
  std::vector<Real> face_area;      // per face, as voro++ computes it
  std::vector<Index> vertex_begin;  // per face, CSR into vertices (size faces + 1)
  std::vector<Vec3> vertices;       // global coordinates, in polygon order

  Index cell_count() const { return static_cast<Index>(volume.size()); }
};

// Voronoi (or radical) tessellation of the particle centres with voro++, clipped by the
// specimen's bounding box.
CellComplex tessellate(const Particles& particles, const SpecimenGeometry& geometry,
                       TessellationKind kind);

}  // namespace rcdem
