#include "rcdem/solver/interaction_nodes.hpp"

#include <algorithm>

namespace rcdem {

InteractionNodes::InteractionNodes(const Specimen& specimen, NodeSet set) : set_(set) {
  std::vector<Index> first_body;  // each bar's first cylinder as a body
  Index first = specimen.concrete();
  for (const Bar& bar : specimen.bars) {
    first_body.push_back(first);
    first += static_cast<Index>(bar.cylinders.size());
  }
  if (set == NodeSet::Ties) {
    for (const BarTie& tie : specimen.ties) {
      nodes_.push_back(make_tie_node(tie, specimen.bars, Quat::Identity(), Quat::Identity()));
      refs_.push_back({first_body[static_cast<std::size_t>(tie.bar_a)] + tie.cylinder_a,
                       first_body[static_cast<std::size_t>(tie.bar_b)] + tie.cylinder_b,
                       tie.bar_a});
    }
  } else {
    for (std::size_t k = 0; k < specimen.bars.size(); ++k) {
      const Bar& bar = specimen.bars[k];
      const std::vector<Quat> reference(bar.cylinders.size(), Quat::Identity());
      const std::vector<InteractionNode> nodes = make_bar_nodes(bar, reference);
      for (std::size_t j = 0; j < nodes.size(); ++j) {
        nodes_.push_back(nodes[j]);
        refs_.push_back(
            {first_body[k] + bar.nodes[j][0], first_body[k] + bar.nodes[j][1], static_cast<int>(k)});
      }
    }
  }
  states_.assign(nodes_.size(), NodeState{});
  forces_.assign(nodes_.size(), NodeForces{});
}

Index InteractionNodes::task_count() const {
  return (static_cast<Index>(nodes_.size()) + kTaskSize - 1) / kTaskSize;
}

void InteractionNodes::run_task(Index task, const StepContext& ctx) {
  const Bodies& b = ctx.bodies;
  const auto begin = static_cast<std::size_t>(task * kTaskSize);
  const std::size_t end = std::min(nodes_.size(), begin + static_cast<std::size_t>(kTaskSize));
  for (std::size_t j = begin; j < end; ++j) {
    const NodeRef& r = refs_[j];
    forces_[j] = evaluate_node(nodes_[j], states_[j], b.position[r.body_a], b.orientation[r.body_a],
                               b.position[r.body_b], b.orientation[r.body_b]);
  }
}

void InteractionNodes::scatter(Bodies& bodies) const {
  for (std::size_t j = 0; j < nodes_.size(); ++j) {
    const NodeRef& r = refs_[j];
    bodies.force[r.body_a] += forces_[j].force_a;
    bodies.torque[r.body_a] += forces_[j].torque_a;
    bodies.force[r.body_b] += forces_[j].force_b;
    bodies.torque[r.body_b] += forces_[j].torque_b;
  }
}

void InteractionNodes::add_dissipation(StepDissipation& d) const {
  for (const NodeForces& f : forces_) d.plastic += f.dissipated;
}

void InteractionNodes::add_strain_energy(Real& sum) const {
  for (std::size_t j = 0; j < nodes_.size(); ++j) sum += node_elastic_energy(nodes_[j], states_[j]);
}

void InteractionNodes::visit_springs(SpringVisitor& v, const Bodies&) const {
  // (9): k_a along the node's axis and k_t across it, at the node; k_b and k_theta as rotational
  // springs. The node's vectors are world vectors at t = 0.
  for (std::size_t j = 0; j < nodes_.size(); ++j) {
    const InteractionNode& node = nodes_[j];
    const Vec3 sum = node.axis_a + node.axis_b;
    const Vec3 axis = sum / sum.norm();
    const Eigen::Matrix3d kr = node.k.bending * (Eigen::Matrix3d::Identity() - axis * axis.transpose()) +
                    node.k.torsion * axis * axis.transpose();
    const NodeRef& r = refs_[j];
    v.spring(r.body_a, r.body_b, node.arm_a, node.arm_b, axis, node.k.axial, node.k.shear);
    v.rotational(r.body_a, r.body_b, kr);
  }
}

}  // namespace rcdem
