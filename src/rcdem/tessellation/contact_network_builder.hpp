#pragma once
// Turns the Voronoi cells into the VGCM-3D contact network (paper 2.1-2.2, SPEC 3): one bonded
// contact per pair of particles sharing a facet of non-zero area, with local points at the
// facet's centroid and vertices.
#include "rcdem/config/scenario.hpp"
#include "rcdem/config/specimen_geometry.hpp"
#include "rcdem/state/contact_network.hpp"
#include "rcdem/state/particles.hpp"
#include "rcdem/tessellation/cell_complex.hpp"

namespace rcdem {

struct NetworkReport {
  Index facets_cut_by_notch = 0;
  Index degenerate_facets = 0;  // shared faces with zero area after merging close vertices
};

ContactNetwork build_contact_network(const Particles& particles, const CellComplex& cells,
                                     const SpecimenGeometry& geometry,
                                     const ContactParameters& parameters,
                                     NetworkReport* report = nullptr,
                                     BoundaryFaces* boundary = nullptr);

}  // namespace rcdem
