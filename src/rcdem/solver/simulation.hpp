#pragma once
// The explicit rigid-particle solver (SPEC 4-6): state, the fixed step pipeline
//   contacts -> plate contacts -> gather per body -> damping + leap-frog -> plates move,
// and the energy ledger. Stop rules, history and snapshots live in the run loop (run.hpp).
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
#include "rcdem/reinforcement/interaction_node.hpp"
#include "rcdem/solver/body_contacts.hpp"
#include "rcdem/solver/critical_time_step.hpp"
#include "rcdem/solver/energy.hpp"
#include "rcdem/solver/loading_rate.hpp"
#include "rcdem/solver/plates.hpp"
#include "rcdem/solver/selective_mass_scaling.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

namespace io {
struct CheckpointAccess;  // run/checkpoint.cpp: saves and restores the state below
}

// A bar pulled out by its first cylinder (pull-out tests): the cylinder's velocity is prescribed
// along `direction`, its rotation held; the force it takes is the pull-out load.
struct PulledBar {
  std::string name;
  Index body = 0;
  Vec3 direction = Vec3::Zero();  // unit, end -> start
  Real speed = 0.0, ramp_time = 0.0;
  Real displacement = 0.0;    // along direction
  Vec3 force = Vec3::Zero();  // on the cylinder from the concrete and the rest of the bar
  Real work = 0.0;
  Real last_step = 0.0;
  Real velocity_at(Real t) const;
  Real load() const { return -force.dot(direction); }
};

class Simulation {
 public:
  // Takes the specimen; the time step is the stable estimate times solver.dt_safety, or the
  // scenario's fixed step (refused above half the critical estimate: dt_safety's upper bound).
  Simulation(const Scenario& scenario, Specimen specimen);

  void step();

  // The estimate the time step is a safety factor of (SPEC 6), with the masses after any
  // selective mass scaling: min over bodies of sqrt(m / sum k) and its rotational analogue
  // ("per_body"), or 2 / omega_max of the assembly ("assembled").
  Real stable_time_step() const { return stable_dt_; }
  // solver.time_step_estimate = "assembled": the assembly's omega_max and how it was found.
  const CriticalTimeStep& critical_time_step() const { return critical_; }
  // Which body and motion set the stable estimate, in words.
  const std::string& stable_time_step_limit() const { return stable_dt_limit_; }
  // solver.added_mass_limit's selective mass scaling, as applied (identity when off).
  const MassScalingPlan& mass_scaling() const { return mass_scaling_; }
  Real time_step() const { return dt_; }
  // loading.adaptive_rate: the factor on every prescribed speed now (1 when off).
  Real loading_rate_factor() const { return loading_rate_.factor(); }
  bool adaptive_loading_rate() const { return loading_rate_.adaptive(); }
  void set_time_step(Real dt) { dt_ = dt; }  // for tests that probe stability
  Real time() const { return time_; }
  std::int64_t steps() const { return steps_; }

  const Specimen& specimen() const { return specimen_; }
  Bodies& bodies() { return bodies_; }
  const Bodies& bodies() const { return bodies_; }
  // The concrete contacts' state. Reading it first brings the histories of contacts evaluated from
  // their sums up to date (contact/elastic_condensation.hpp): the points read as if every one had
  // been visited every step.
  const ContactState& contacts() const {
    catch_up_condensed_points();
    return contacts_;
  }
  ContactState& contacts() {
    catch_up_condensed_points();
    return contacts_;
  }
  // Concrete contacts evaluated from their sums at the last step (0 when condensation is off,
  // and after a read of the state above has brought their points up to date).
  Index condensed_contacts() const { return condensation_.condensed_count(); }
  Index condensed_points() const { return condensation_.condensed_point_count(specimen_.contacts); }
  // Brings condensed contacts' point histories up to the last step (contacts() does it).
  void catch_up_condensed_points() const;
  std::vector<Plate>& plates() { return plates_; }
  const std::vector<Plate>& plates() const { return plates_; }
  const PlateContacts& plate_contacts() const { return plate_contacts_; }
  const Plate* find_plate(const std::string& name) const;
  const PulledBar* find_pulled_bar(const std::string& name) const;
  const std::vector<PulledBar>& pulled_bars() const { return pulled_; }
  // The ledger now. The strain energy is a function of the state, summed here on demand (the
  // loop does not compute it every step: two divisions per local point).
  Energy energy() const;
  Real strain_energy() const;  // without bringing condensed contacts' histories up to date
  // The ledger's running sums (work, kinetic energy, dissipation) without the strain energy
  // (left 0): no sweep over the local points, for use every step.
  const Energy& ledger() const { return energy_; }

  // The bars (SPEC 7-8): cylinders are bodies [concrete_count, size); nodes join consecutive ones.
  Index concrete_count() const { return specimen_.concrete(); }
  struct NodeRef {
    Index body_a, body_b;
    int bar;
  };
  const std::vector<NodeRef>& nodes() const { return node_refs_; }
  const std::vector<InteractionNode>& node_constants() const { return nodes_; }
  const std::vector<NodeState>& node_states() const { return node_states_; }
  const std::vector<NodeForces>& node_forces() const { return node_forces_; }
  const std::vector<ContactState>& interface_contacts() const { return interface_states_; }
  Index yielded_nodes() const;
  Real max_axial_force() const;  // largest |N| over the nodes

  // Every concrete local point's damage D, current without a catch-up (a condensed contact's points
  // are intact: their stale histories hold D = 0, as the current ones would).
  PointDamage point_damage() const { return contacts_.point.damage(); }
  Index damaged_points() const;  // 0 < D < 1, concrete contacts
  Index broken_points() const;   // D = 1, concrete contacts
  Index broken_interface_points() const;

  // Steps without the damping term or plates, for verification tests.
  void set_damping(Real alpha) { damping_ = alpha; }

 private:
  friend struct io::CheckpointAccess;
  void compute_stable_time_step(Real added_mass_limit, TimeStepEstimate estimate,
                                const std::string& source);
  // Calls v.network(net, normals), v.spring(a, b, arm_a, arm_b, n, kn, ks) (a < 0: a plate) and
  // v.rotational(a, b, k) for every spring of SPEC 6's estimates, at t = 0.
  template <class Visitor>
  void visit_springs(Visitor&& v) const;
  ContactInputs concrete_inputs(const std::vector<Vec3>& positions,
                                const std::vector<Eigen::Matrix3d>& rotation) const;
  void gather_forces();
  void integrate();
  Real concrete_strain_energy() const;

  Specimen specimen_;
  Bodies bodies_;
  // Mutable: condensed contacts' point histories are filled in when first read (logically const).
  mutable ContactState contacts_;
  mutable ElasticCondensation condensation_;  // empty when off or for the EL law
  // The bodies' centres at the last evaluation and the one before (with rotation_prev_).
  std::vector<Vec3> position_eval_, position_prev_;
  BodyContacts body_contacts_;
  std::vector<Plate> plates_;
  PlateContacts plate_contacts_;
  ContactLaw law_;                              // the concrete's (contact.law)
  std::vector<ContactState> interface_states_;  // per bar
  std::vector<ContactLaw> interface_law_;       // per bar
  std::vector<InteractionNode> nodes_;
  std::vector<NodeRef> node_refs_;
  std::vector<NodeState> node_states_;
  std::vector<NodeForces> node_forces_;
  std::vector<PulledBar> pulled_;
  std::vector<std::int64_t> driven_;  // per body: index into pulled_, or -1
  std::vector<Real> pulled_force_prev_;
  Real damping_;
  Real dt_ = 0.0, stable_dt_ = 0.0;
  std::string stable_dt_limit_;
  CriticalTimeStep critical_;
  LoadingRate loading_rate_;
  MassScalingPlan mass_scaling_;
  Real time_ = 0.0;
  std::int64_t steps_ = 0;
  Energy energy_;
  std::vector<Real> plate_force_prev_, plate_displacement_prev_;
  std::vector<Real> body_damping_work_, body_kinetic_;
  std::vector<std::int64_t> body_jumped_;
  // Per block of kSphereBlock concrete particles (integrate()): their sums of the three above.
  static constexpr Index kSphereBlock = 128;
  struct SphereBlockSums {
    Real damping_work = 0.0, kinetic = 0.0;
    std::int64_t jumped = 0;
  };
  std::vector<SphereBlockSums> sphere_block_sums_;
  // The small networks (interface contacts of every bar, plate contacts, interaction nodes) as one
  // list of tasks of a few dozen items each, run in one parallel region: bar by bar each was below
  // parallel_for's threshold and ran on one thread while the other waited (a tenth of an elastic
  // beam step at 2 threads).
  struct SmallTask {
    enum Kind { kInterface, kPlates, kNodes } kind;
    std::size_t bar;  // kInterface: which bar's network
    Index begin, end;
  };
  std::vector<SmallTask> small_tasks_;
  void run_small_task(const SmallTask& task);
  Index spheres_ = 0;  // bodies [0, spheres_) take advance_spheres()
  // Every body's orientation as a matrix, formed at the start of each step for the contact loops
  // (derived from the orientations: not part of a checkpoint).
  std::vector<Eigen::Matrix3d> rotation_, rotation_prev_;
  BodyPoses pose_;  // the same with the centres, for the condensed contacts' kernel
  mutable std::vector<Real> strain_energy_blocks_;  // concrete_strain_energy()'s per-block sums
};

}  // namespace rcdem
