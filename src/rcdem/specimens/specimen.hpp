#pragma once
// A generated specimen: its geometry, particles and VGCM-3D contact network, and what generation
// measured on the way.
#include "rcdem/config/scenario.hpp"
#include "rcdem/config/specimen_geometry.hpp"
#include "rcdem/packing/generator.hpp"
#include "rcdem/reinforcement/bar_builder.hpp"
#include "rcdem/reinforcement/bar_ties.hpp"
#include "rcdem/state/contact_network.hpp"
#include "rcdem/state/particles.hpp"
#include "rcdem/tessellation/contact_network_builder.hpp"
#include "rcdem/tessellation/interface_network_builder.hpp"

namespace rcdem {

// Particles are the concrete ones [0, concrete_count) then the bars' interface spheres; the
// solver's bodies are the concrete particles (same indices) then the bars' cylinders, bar by bar.
struct Specimen {
  SpecimenGeometry geometry;
  Particles particles;
  Index concrete_count = -1;  // -1: every particle is concrete (a specimen without bars)
  Index concrete() const { return concrete_count < 0 ? particles.size() : concrete_count; }
  ContactNetwork contacts;                    // concrete-concrete
  std::vector<Bar> bars;                      // SPEC 7
  std::vector<BarTie> ties;                   // where two bars touch (reinforcement/bar_ties.hpp)
  SteelSpheres steel;                         // the interface spheres (SPEC 8)
  std::vector<InterfaceContacts> interfaces;  // one per bar
  BoundaryFaces boundary;
  PackingReport packing;
  NetworkReport network;
};

// Generation (SPEC 2) then tessellation and the contact network (SPEC 3).
Specimen build_specimen(const Scenario& scenario);

}  // namespace rcdem
