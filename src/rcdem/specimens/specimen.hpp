#pragma once
// A generated specimen: its geometry, particles and VGCM-3D contact network, and what generation
// measured on the way.
#include "rcdem/io/scenario.hpp"
#include "rcdem/packing/generator.hpp"
#include "rcdem/specimens/specimen_geometry.hpp"
#include "rcdem/state/contact_network.hpp"
#include "rcdem/state/particles.hpp"
#include "rcdem/tessellation/contact_network_builder.hpp"

namespace rcdem {

struct Specimen {
  SpecimenGeometry geometry;
  Particles particles;
  ContactNetwork contacts;
  BoundaryFaces boundary;
  PackingReport packing;
  NetworkReport network;
};

// Generation (SPEC 2) then tessellation and the contact network (SPEC 3).
Specimen build_specimen(const Scenario& scenario);

}  // namespace rcdem
