#pragma once
// The bars' interaction nodes as a part of the step (solver/step_part.hpp; SPEC 7, paper 2.5):
// every node joining two consecutive cylinders of a bar, bar by bar, with its state; or, as a
// second part of the same kind, the ties where two bars touch (reinforcement/bar_ties.hpp).
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/archive.hpp"
#include "rcdem/reinforcement/interaction_node.hpp"
#include "rcdem/solver/step_part.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace rcdem {

// The two cylinders an interaction node joins, and its bar (a tie: the first of its two bars).
struct NodeRef {
  Index body_a, body_b;
  int bar;
};

enum class NodeSet { Bars, Ties };

class InteractionNodes final : public StepPart {
 public:
  static constexpr Index kTaskSize = 64;  // nodes per task

  // The nodes of the specimen's bars (NodeSet::Bars) or its ties (NodeSet::Ties), whose
  // cylinders are bodies from specimen.concrete() on (their orientations at t = 0 are the nodes'
  // reference: identity).
  InteractionNodes(const Specimen& specimen, NodeSet set);

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

  // The checkpoint's "nodes", or "ties" where there are any (so that the checkpoints of the runs
  // without ties keep their format; core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    if (s.set_ == NodeSet::Bars || !s.states_.empty())
      ar.table(s.set_ == NodeSet::Bars ? "nodes" : "ties", s.states_.size(),
               column("state", "", s.states_), column("forces", "", s.forces_));
  }

 private:
  NodeSet set_;
  std::vector<InteractionNode> nodes_;  // constants (9)
  std::vector<NodeRef> refs_;
  std::vector<NodeState> states_;
  std::vector<NodeForces> forces_;
};

}  // namespace rcdem
