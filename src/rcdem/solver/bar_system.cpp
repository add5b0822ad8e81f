#include "rcdem/solver/bar_system.hpp"

#include "rcdem/tessellation/interface_network_builder.hpp"

namespace rcdem {

BarSystem BarSystem::build(const Scenario& sc, const Specimen& specimen, const Bodies& bodies) {
  BarSystem s;
  // Interaction nodes, built with the cylinders' orientations at t = 0 as stored here (identity:
  // rotations since t = 0).
  Index first = specimen.concrete();
  for (std::size_t k = 0; k < specimen.bars.size(); ++k) {
    const Bar& bar = specimen.bars[k];
    const std::vector<Quat> reference(bar.cylinders.size(), Quat::Identity());
    const std::vector<InteractionNode> nodes = make_bar_nodes(bar, reference);
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      s.nodes.push_back(nodes[j]);
      s.node_refs.push_back(
          {first + bar.nodes[j][0], first + bar.nodes[j][1], static_cast<int>(k)});
    }
    first += static_cast<Index>(bar.cylinders.size());
  }
  s.node_states.assign(s.nodes.size(), NodeState{});
  s.node_forces.assign(s.nodes.size(), NodeForces{});
  // The interface contacts of each bar, with its law (paper 3: EL, NL-A, NL-B).
  for (std::size_t k = 0; k < specimen.interfaces.size(); ++k) {
    const InterfaceContacts& ic = specimen.interfaces[k];
    std::vector<Vec3> axes(ic.anchor0.size());
    for (std::size_t c = 0; c < axes.size(); ++c)
      axes[c] = bodies.orientation0[ic.net.particle_b[c]] * Vec3::UnitZ();
    ContactState state;
    state.init(ic.net, bodies.position, &ic.anchor0, &axes);
    s.interface_states.push_back(std::move(state));
    const BarSettings& bar = sc.bars[k];
    s.interface_law.push_back(
        make_contact_law(bar.interface == InterfaceLaw::EL ? "EL" : bar.interface_softening,
                         interface_parameters(sc.contact, bar), "bars.*.interface_softening"));
  }
  return s;
}

}  // namespace rcdem
