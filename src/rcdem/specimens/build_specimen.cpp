#include "rcdem/specimens/specimen.hpp"
#include "rcdem/specimens/specimen_registry.hpp"
#include "rcdem/tessellation/cell_complex.hpp"

namespace rcdem {

Specimen build_specimen(const Scenario& scenario) {
  Specimen s;
  s.geometry = specimen_geometry(scenario);
  s.particles = generate_packing(scenario.generation, s.geometry, &s.packing);
  const CellComplex cells = tessellate(s.particles, s.geometry, scenario.tessellation);
  s.particles.cell_volume = cells.volume;
  s.contacts = build_contact_network(s.particles, cells, s.geometry, scenario.contact, &s.network,
                                     &s.boundary);
  return s;
}

}  // namespace rcdem
