#pragma once
// The explicit rigid-particle solver (SPEC 4-6): the bodies, the parts of the step
// (solver/step_part.hpp: the concrete network, each bar's interface, the interaction nodes, the
// pulled bars, the plates), and the step as their composition
//   evaluate -> scatter -> integrate -> drive -> ledger.
// Stop rules, history and snapshots live in the run loop (run.hpp).
#include <memory>
#include <utility>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/solver/bar_interface.hpp"
#include "rcdem/solver/concrete_contacts.hpp"
#include "rcdem/solver/energy.hpp"
#include "rcdem/solver/integrator.hpp"
#include "rcdem/solver/interaction_nodes.hpp"
#include "rcdem/solver/loading_rate.hpp"
#include "rcdem/solver/plates.hpp"
#include "rcdem/solver/pulled_bars.hpp"
#include "rcdem/solver/rank_exchange.hpp"
#include "rcdem/solver/step_part.hpp"
#include "rcdem/solver/time_step_choice.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

class Simulation {
 public:
  // Takes the specimen; the time step is the stable estimate times solver.dt_safety, or the
  // scenario's fixed step (refused above half the critical estimate: dt_safety's upper bound).
  Simulation(const Scenario& scenario, Specimen specimen);
  // The parts point into the specimen and the bodies: a simulation stays where it was built.
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  void step();

  // A distributed run (docs/parallel.md): from now on this rank steps its share of the simulation
  // (solver/decomposition.hpp) and exchanges the rest through `comm`, which must outlive it. Rank
  // 0 then drives the others: step, strain_energy, catch_up_condensed_points, bodies,
  // keep_strain_energy_every and exchange_seconds_by_rank first send them the same request; the
  // others call follow().
  // `leader_reads`: spheres rank 0 reads between steps every step (the gauges' particles): it
  // receives them as ghosts instead of gathering every sphere.
  void distribute(Communicator& comm, const std::vector<Index>& leader_reads = {});
  // A rank other than 0: serves rank 0's requests until one it does not serve, which it returns
  // (RankCommand::Restore, Finish).
  RankMessage follow();
  // Rank 0's message to the other ranks (nothing when not distributed or on another rank).
  void tell_ranks(RankCommand command, std::int64_t value = 0) const;
  const RankExchange* exchange() const { return exchange_.get(); }
  // Rank 0: every rank's exchange time by kind since its loop's first step (collective).
  std::vector<ExchangeSeconds> exchange_seconds_by_rank() const;

  // The estimate the time step is a safety factor of (SPEC 6), with the masses after any
  // selective mass scaling: min over bodies of sqrt(m / sum k) and its rotational analogue
  // ("per_body"), or 2 / omega_max of the assembly ("assembled").
  Real stable_time_step() const { return time_step_.stable; }
  // solver.time_step_estimate = "assembled": the assembly's omega_max and how it was found.
  const CriticalTimeStep& critical_time_step() const { return time_step_.critical; }
  // Which body and motion set the stable estimate, in words.
  const std::string& stable_time_step_limit() const { return time_step_.limit; }
  // solver.added_mass_limit's selective mass scaling, as applied (identity when off).
  const MassScalingPlan& mass_scaling() const { return time_step_.mass_scaling; }
  Real time_step() const { return time_step_.dt; }
  // loading.adaptive_rate: the factor on every prescribed speed now (1 when off).
  Real loading_rate_factor() const { return loading_rate_.factor(); }
  bool adaptive_loading_rate() const { return loading_rate_.adaptive(); }
  void set_time_step(Real dt) { time_step_.dt = dt; }  // for tests that probe stability
  Real time() const { return time_; }
  std::int64_t steps() const { return steps_; }

  const Specimen& specimen() const { return specimen_; }
  // The bodies. Distributed, reading them first brings rank 0's copy of every sphere's motion up
  // to date (the step sends it only the spheres it reads).
  Bodies& bodies() {
    catch_up_bodies();
    return bodies_;
  }
  const Bodies& bodies() const {
    catch_up_bodies();
    return bodies_;
  }
  // The concrete contacts' state. Reading it first brings the histories of contacts evaluated from
  // their sums up to date (contact/elastic_condensation.hpp): the points read as if every one had
  // been visited every step.
  const ContactState& contacts() const {
    catch_up_condensed_points();
    return concrete_.state();
  }
  ContactState& contacts() {
    catch_up_condensed_points();
    return concrete_.state();
  }
  // Concrete contacts evaluated from their sums at the last step (0 when condensation is off,
  // and after a read of the state above has brought their points up to date).
  Index condensed_contacts() const { return concrete_.condensation().condensed_count(); }
  Index held_contacts() const { return concrete_.condensation().held.count(); }
  Index condensed_points() const {
    return concrete_.condensation().condensed_point_count(specimen_.contacts);
  }
  Index held_points() const {  // the held contacts' local points
    return concrete_.condensation().held_point_count(specimen_.contacts);
  }
  // The bodies as the step left them on this rank, without gathering: distributed, current are
  // only its own spheres, its ghosts, the cylinders and, on rank 0, the `leader_reads` of
  // distribute(). For readers of those alone (a gauge every step).
  const Bodies& bodies_as_stepped() const { return bodies_; }
  // Brings condensed contacts' point histories up to the last step (contacts() does it).
  void catch_up_condensed_points() const;
  // Rank 0 of a distributed run: every sphere's motion gathered from its owner, once per step
  // (bodies() does it).
  void catch_up_bodies() const;
  std::vector<Plate>& plates() { return plates_.plates; }
  const std::vector<Plate>& plates() const { return plates_.plates; }
  const PlateContacts& plate_contacts() const { return plates_.contacts; }
  const Plate* find_plate(const std::string& name) const;
  const PulledBar* find_pulled_bar(const std::string& name) const;
  const std::vector<PulledBar>& pulled_bars() const { return pulled_.bars; }
  std::vector<PulledBar>& pulled_bars() { return pulled_.bars; }
  // The parts in the step's order (solver/step_part.hpp).
  const std::vector<StepPart*>& parts() const { return parts_; }
  // The ledger now. The strain energy is a function of the state, summed here on demand (the
  // loop does not compute it every step: two divisions per local point).
  Energy energy() const;
  Real strain_energy() const;  // without bringing condensed contacts' histories up to date
  // Steps whose number is a multiple of n (0: none) keep their strain energy while they evaluate
  // (StepContext::report_strain_energy): a run sets its history's spacing, so that a row's
  // strain_energy() costs no pass over the contacts. The value is the same either way.
  void keep_strain_energy_every(std::int64_t n) {
    tell_ranks(RankCommand::KeepStrainEnergy, n);
    strain_energy_every_ = n;
  }
  // The ledger's running sums (work, kinetic energy, dissipation) without the strain energy
  // (left 0): no sweep over the local points, for use every step.
  const Energy& ledger() const { return energy_; }

  // The bars (SPEC 7-8): cylinders are bodies [concrete_count, size); nodes join consecutive ones.
  Index concrete_count() const { return specimen_.concrete(); }
  const std::vector<NodeRef>& nodes() const { return nodes_.refs(); }
  const std::vector<InteractionNode>& node_constants() const { return nodes_.constants(); }
  const std::vector<NodeState>& node_states() const { return nodes_.states(); }
  const std::vector<NodeForces>& node_forces() const { return nodes_.forces(); }
  // The ties where two bars touch (reinforcement/bar_ties.hpp), in the specimen's order of ties.
  const InteractionNodes& ties() const { return ties_; }
  // Each bar's interface, in the specimen's order of interfaces.
  const std::vector<std::unique_ptr<BarInterface>>& interfaces() const { return interfaces_; }
  Index yielded_nodes() const;
  Real max_axial_force() const;  // largest |N| over the nodes

  // Every concrete local point's damage D, current without a catch-up (a condensed contact's points
  // are intact: their stale histories hold D = 0, as the current ones would).
  PointDamage point_damage() const { return concrete_.state().point.damage(); }
  // Kept by the step (ContactState's counters), not counted per call.
  Index damaged_points() const;  // 0 < D < 1, concrete contacts
  Index broken_points() const;   // D = 1, concrete contacts
  // The concrete contacts in which points broke, one entry per contact and step since the
  // simulation was made or restored (ContactState::broken_contact_log).
  const std::vector<Index>& broken_contact_log() const {
    return concrete_.state().broken_contact_log;
  }
  Index broken_interface_points() const;

  // Steps without the damping term or plates, for verification tests.
  void set_damping(Real alpha) { integrator_.set_damping(alpha); }

  // The checkpoint's sections of the simulation, in the file's order (core/archive.hpp; defined in
  // solver/simulation_archive.hpp). Saving expects the condensed contacts caught up; restoring
  // leaves none condensed.
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s);

 private:
  void compute_stable_time_step(Real added_mass_limit, TimeStepEstimate estimate,
                                const std::string& source);
  // Every spring of SPEC 6's estimates at t = 0, part by part.
  void visit_springs(SpringVisitor& v) const;
  StepContext context() {
    return {bodies_, kinematics_, clock(),
            strain_energy_every_ > 0 && (steps_ + 1) % strain_energy_every_ == 0};
  }
  StepClock clock() const { return {time_, time_step_.dt, loading_rate_.factor()}; }
  void run_part_tasks();
  // The integration and, distributed, the exchange of the spheres; true if rank 0 must report an
  // instability.
  bool advance();
  void check_stability() const;
  // Every rank's share of the contacts' and bodies' state onto rank 0 (RankCommand::GatherState).
  void gather_state();
  void book_step();

  Specimen specimen_;
  Bodies bodies_;
  BodyKinematics kinematics_;
  PrescribedMotion prescribed_;
  ConcreteContacts concrete_;
  std::vector<std::unique_ptr<BarInterface>> interfaces_;
  InteractionNodes nodes_;
  InteractionNodes ties_;  // where two bars touch
  PulledBars pulled_;
  PlateSet plates_;
  // The step's order (evaluation, scatter, drive), and the ledger's: the dissipation and strain
  // energy summed as the ledger first summed them (concrete, plates, bars), so that the golden
  // references' energies are the same bits. A new part goes last in both.
  std::vector<StepPart*> parts_, ledger_order_;
  // Every part's small tasks (part, task), run in one parallel region.
  std::vector<std::pair<StepPart*, Index>> tasks_;
  Integrator integrator_;
  TimeStepChoice time_step_;
  LoadingRate loading_rate_;
  Real time_ = 0.0;
  std::int64_t steps_ = 0;
  std::int64_t strain_energy_every_ = 0;  // keep_strain_energy_every
  Energy energy_;
  std::unique_ptr<RankExchange> exchange_;  // distributed runs only
  std::int64_t gathered_step_ = -1;         // the step whose state rank 0 last gathered
  // The step whose motion rank 0 last gathered: at 0 (and after a restore) every rank holds it.
  mutable std::int64_t motion_step_ = 0;
};

}  // namespace rcdem
