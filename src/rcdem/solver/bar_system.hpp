#pragma once
// The bars' side of the model (SPEC 7-8): each bar's interface contacts with their law, and the
// interaction nodes joining consecutive cylinders with their state. Built once from the specimen;
// the bars' cylinders are bodies [concrete, size) of the solver's Bodies.
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
#include "rcdem/reinforcement/interaction_node.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

// The two cylinders an interaction node joins, and its bar.
struct NodeRef {
  Index body_a, body_b;
  int bar;
};

struct BarSystem {
  std::vector<ContactState> interface_states;  // per bar
  std::vector<ContactLaw> interface_law;       // per bar (paper 3: EL, NL-A, NL-B)
  std::vector<InteractionNode> nodes;          // constants (9)
  std::vector<NodeRef> node_refs;
  std::vector<NodeState> node_states;
  std::vector<NodeForces> node_forces;

  // From the specimen's bars and interfaces, with the cylinders already among `bodies` (their
  // orientations at t = 0 are the nodes' reference: identity).
  static BarSystem build(const Scenario& sc, const Specimen& specimen, const Bodies& bodies);

  // The checkpoint's "interface.<bar>" sections and "nodes" (core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    for (std::size_t k = 0; k < s.interface_states.size(); ++k)
      ContactState::serialize(ar, "interface." + std::to_string(k), s.interface_states[k]);
    ar.table("nodes", s.node_states.size(), column(s.node_states), column(s.node_forces));
  }
};

}  // namespace rcdem
