#pragma once
// The steel-concrete interface contacts (paper 2.6, SPEC 8). The interface spheres take part in
// the tessellation; a concrete particle's facets with the spheres of one bar are merged into a
// single contact (total area; the local points of the largest facet, their areas scaled to the
// total), attached to the nearest sphere's cylinder. Facets between steel spheres are not
// contacts.
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/state/contact_network.hpp"
#include "rcdem/state/particles.hpp"
#include "rcdem/tessellation/cell_complex.hpp"

namespace rcdem {

// Per steel particle (kind Steel): its bar and the body index of its cylinder.
struct SteelSpheres {
  std::vector<int> bar;
  std::vector<Index> body;
  Index first = 0;  // steel particles are [first, first + size) of Particles
};

// The interface contact parameters of a bar: NL-A and EL use the concrete's, NL-B halves
// sigma_n,t and tau (paper 3); the bar's interface_strength_scale then multiplies sigma_n,t and
// tau, and its interface_energy_scale G_fn and G_fs (studies of the bond beyond the paper's two
// variants).
ContactParameters interface_parameters(const ContactParameters& concrete, const BarSettings& bar);

std::vector<InterfaceContacts> build_interface_contacts(const Particles& particles,
                                                        const CellComplex& cells,
                                                        const SteelSpheres& steel,
                                                        const std::vector<BarSettings>& bars,
                                                        const ContactParameters& concrete);

}  // namespace rcdem
