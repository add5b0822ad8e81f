#pragma once
// The bars' interaction nodes as a part of the step (solver/step_part.hpp; SPEC 7, paper 2.5):
// every node joining two consecutive cylinders of a bar, bar by bar, with its state.
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/reinforcement/interaction_node.hpp"
#include "rcdem/solver/step_part.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace rcdem {

// The two cylinders an interaction node joins, and its bar.
struct NodeRef {
  Index body_a, body_b;
  int bar;
};

class InteractionNodes final : public StepPart {
 public:
  static constexpr Index kTaskSize = 64;  // nodes per task

  // The nodes of the specimen's bars, whose cylinders are bodies from specimen.concrete() on
  // (their orientations at t = 0 are the nodes' reference: identity).
  explicit InteractionNodes(const Specimen& specimen);

  Index task_count() const override;
  void run_task(Index task, const StepContext& ctx) override;
  void scatter(Bodies& bodies) const override;
  void add_dissipation(StepDissipation& d) const override;
  void add_strain_energy(Real& sum) const override;
  void visit_springs(SpringVisitor& v, const Bodies& bodies) const override;

  std::size_t size() const { return nodes_.size(); }
  const std::vector<InteractionNode>& constants() const { return nodes_; }
  const std::vector<NodeRef>& refs() const { return refs_; }
  const std::vector<NodeState>& states() const { return states_; }
  const std::vector<NodeForces>& forces() const { return forces_; }

  // The checkpoint's "nodes" (core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    ar.table("nodes", s.states_.size(), column(s.states_), column(s.forces_));
  }

 private:
  std::vector<InteractionNode> nodes_;  // constants (9)
  std::vector<NodeRef> refs_;
  std::vector<NodeState> states_;
  std::vector<NodeForces> forces_;
};

}  // namespace rcdem
