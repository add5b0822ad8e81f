#include "rcdem/solver/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rcdem/contact/law_loops.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/parallel.hpp"
#include "rcdem/reinforcement/rigid_rotation.hpp"
#include "rcdem/solver/assembled_stiffness.hpp"
#include "rcdem/solver/body_stiffness.hpp"
#include "rcdem/solver/selective_mass_scaling.hpp"
#include "rcdem/solver/sphere_update.hpp"

namespace rcdem {

namespace {
// The concrete particles as bodies, then the bars' cylinders: exact mass and inertia (SPEC 7),
// principal frame z along the axis.
Bodies make_bodies(const Scenario& sc, const Specimen& specimen) {
  Bodies bodies = bodies_from_particles(specimen.particles, sc.solver.density,
                                        sc.solver.mass_scaling, specimen.concrete());
  for (Vec3& inertia : bodies.inertia) inertia *= sc.solver.particle_rotational_inertia_scaling;
  for (const Bar& bar : specimen.bars)
    for (const auto& cyl : bar.cylinders) {
      CylinderInertia in = solid_cylinder_inertia(bar.diameter, cyl.length, bar.steel.density);
      in.principal_inertia *= sc.solver.bar_rotational_inertia_scaling;
      add_body(bodies, cyl.centre, sc.solver.mass_scaling * in.mass,
               sc.solver.mass_scaling * in.principal_inertia, orientation_for_axis(cyl.axis),
               0.5 * bar.diameter);
    }
  return bodies;
}
}  // namespace

Simulation::Simulation(const Scenario& sc, Specimen specimen)
    : specimen_(std::move(specimen)),
      bodies_(make_bodies(sc, specimen_)),
      kinematics_(bodies_),
      prescribed_(bodies_.size()),
      concrete_(sc, specimen_.contacts, bodies_, kinematics_),
      nodes_(specimen_, NodeSet::Bars),
      ties_(specimen_, NodeSet::Ties),
      pulled_(sc, specimen_, prescribed_),
      plates_(sc.plates, specimen_.geometry, specimen_.boundary, bodies_, sc.contact),
      integrator_(bodies_, prescribed_, sc.solver.damping),
      loading_rate_(sc.loading_rate) {
  for (std::size_t k = 0; k < specimen_.interfaces.size(); ++k)
    interfaces_.push_back(std::make_unique<BarInterface>(k, sc.bars[k], sc.contact,
                                                         specimen_.interfaces[k], bodies_));
  parts_.push_back(&concrete_);
  for (const auto& p : interfaces_) parts_.push_back(p.get());
  parts_.push_back(&nodes_);
  parts_.push_back(&pulled_);
  parts_.push_back(&plates_);
  parts_.push_back(&ties_);
  ledger_order_.push_back(&concrete_);
  ledger_order_.push_back(&plates_);
  for (const auto& p : interfaces_) ledger_order_.push_back(p.get());
  ledger_order_.push_back(&nodes_);
  ledger_order_.push_back(&pulled_);
  ledger_order_.push_back(&ties_);
  for (StepPart* p : parts_)
    for (Index t = 0; t < p->task_count(); ++t) tasks_.emplace_back(p, t);
  compute_stable_time_step(sc.solver.added_mass_limit, sc.solver.estimate, sc.source.string());
  time_step_.dt = sc.solver.dt_safety * time_step_.stable;
  if (sc.solver.time_step > 0.0) {
    const Real most = max_dt_safety(sc.solver.estimate);
    if (sc.solver.time_step > most * time_step_.stable)
      fail(
          "{}: key 'solver.time_step' ({:.4g} s) is above the stable limit: at most {} x the "
          "critical estimate {:.4g} s = {:.4g} s",
          sc.source.string(), sc.solver.time_step, most, time_step_.stable,
          most * time_step_.stable);
    time_step_.dt = sc.solver.time_step;
  }
}

void Simulation::catch_up_condensed_points() const {
  if (!exchange_ || gathered_step_ == steps_) {
    concrete_.catch_up(time_step_.dt);
    return;
  }
  tell_ranks(RankCommand::GatherState);
  // Logically const: rank 0's copy of the other ranks' share, brought up to date.
  const_cast<Simulation*>(this)->gather_state();
}

void Simulation::catch_up_bodies() const {
  if (!exchange_ || !exchange_->leader() || motion_step_ == steps_) return;
  tell_ranks(RankCommand::GatherMotion);
  // Logically const: rank 0's copy of the other ranks' spheres, brought up to date.
  exchange_->gather_motion(const_cast<Bodies&>(bodies_));
  motion_step_ = steps_;
}

void Simulation::gather_state() {
  concrete_.catch_up(time_step_.dt);
  concrete_.gather_held();
  exchange_->gather_state(concrete_.state(), specimen_.contacts, bodies_, integrator_.step_sums());
  gathered_step_ = motion_step_ = steps_;
}

void Simulation::distribute(Communicator& comm, const std::vector<Index>& leader_reads) {
  const Index spheres = integrator_.step_sums().spheres;
  if (spheres != specimen_.concrete())
    fail(
        "a distributed run needs every concrete particle free and isotropic and no bar cylinder "
        "isotropic ({} leading isotropic bodies, {} particles); run it on one rank",
        spheres, specimen_.concrete());
  Decomposition d = Decomposition::build(specimen_.contacts, spheres, comm.rank(), comm.size());
  concrete_.distribute(d, comm);
  const auto r = static_cast<std::size_t>(d.rank);
  integrator_.share_spheres(d.sphere_offsets[r], d.sphere_offsets[r + 1]);
  // The spheres the parts every rank evaluates read: the bars' interfaces and the plates'.
  std::vector<Index> shared;
  for (const InterfaceContacts& in : specimen_.interfaces)
    shared.insert(shared.end(), in.net.particle_a.begin(), in.net.particle_a.end());
  shared.insert(shared.end(), plates_.contacts.particle.begin(), plates_.contacts.particle.end());
  if (comm.leader()) shared.insert(shared.end(), leader_reads.begin(), leader_reads.end());
  exchange_ = std::make_unique<RankExchange>(comm, std::move(d), specimen_.contacts, shared);
  kinematics_.only = exchange_->read_bodies(bodies_.size());
}

std::vector<ExchangeSeconds> Simulation::exchange_seconds_by_rank() const {
  tell_ranks(RankCommand::ExchangeTimes);
  return exchange_->gather_seconds();
}

void Simulation::tell_ranks(RankCommand command, std::int64_t value) const {
  if (exchange_ && exchange_->leader()) exchange_->exchange({command, value});
}

RankMessage Simulation::follow() {
  bool stepped = false;
  for (;;) {
    const RankMessage m = exchange_->exchange({});
    switch (m.command) {
      case RankCommand::Step:
        // The exchange times count from the loop's first step, as rank 0's do (the set-up's
        // waits for rank 0 are not the step's cost).
        if (!stepped) exchange_->reset_seconds();
        stepped = true;
        step();
        break;
      case RankCommand::ExchangeTimes:
        (void)exchange_->gather_seconds();
        break;
      case RankCommand::StrainEnergy:
        (void)strain_energy();
        break;
      case RankCommand::GatherState:
        gather_state();
        break;
      case RankCommand::GatherMotion:
        exchange_->gather_motion(bodies_);
        break;
      case RankCommand::KeepStrainEnergy:
        strain_energy_every_ = m.value;
        break;
      default:
        return m;
    }
  }
}

const PulledBar* Simulation::find_pulled_bar(const std::string& name) const {
  return pulled_.find(name);
}

const Plate* Simulation::find_plate(const std::string& name) const { return plates_.find(name); }

void Simulation::step() {
  tell_ranks(RankCommand::Step);
  const TallyMark before = TallyMark::of(concrete_.state());
  kinematics_.update(bodies_);  // the poses every part's evaluation reads
  const StepContext ctx = context();
  for (StepPart* p : parts_) p->evaluate(ctx);
  run_part_tasks();
  for (StepPart* p : parts_) p->finish_evaluation();
  if (exchange_) {
    exchange_->share_dissipation(concrete_.state());
    exchange_->gather_transitions(concrete_.state(), specimen_.contacts, before);
  }
  for (StepPart* p : parts_) p->scatter(bodies_);  // the first assigns, the rest add
  for (StepPart* p : parts_) p->prescribe(prescribed_, ctx.clock);
  if (advance()) check_stability();
  for (StepPart* p : parts_) p->drive(bodies_, ctx.clock, energy_);
  book_step();
}

bool Simulation::advance() {
  const bool jumped = integrator_.advance(bodies_, prescribed_, time_step_.dt);
  if (!exchange_) return jumped;
  exchange_->share_spheres(bodies_, integrator_.step_sums());
  if (!integrator_.jumped()) return false;
  exchange_->share_jumps(integrator_.step_sums());
  exchange_->gather_motion(bodies_);  // the message names the body's speed
  // Rank 0 reports it; the others wait for its RankCommand::Finish.
  return exchange_->leader();
}

void Simulation::run_part_tasks() {
  const StepContext ctx = context();
  parallel_tasks(static_cast<Index>(tasks_.size()), [&](Index j) {
    const auto& [part, task] = tasks_[static_cast<std::size_t>(j)];
    part->run_task(task, ctx);
  });
}

void Simulation::book_step() {
  // What this step dissipated, summed in a fixed order (deterministic), then the clock.
  StepDissipation d;
  for (const StepPart* p : ledger_order_) p->add_dissipation(d);
  energy_.plastic += d.plastic;
  Real damping_work = 0.0, kinetic = 0.0;
  integrator_.add_energies(damping_work, kinetic);
  energy_.damage += d.damage;
  energy_.friction += d.friction;
  energy_.damping += damping_work;
  energy_.kinetic = kinetic;
  time_ += time_step_.dt;
  ++steps_;
  loading_rate_.update(steps_, time_step_.dt, energy_);
}

void Simulation::check_stability() const {
  const Index i = integrator_.first_jumped();
  fail(
      "numerical instability at step {} (t = {:.6g} s): body {} moved {:.3g} m in one step "
      "(time step {:.4g} s, stable estimate {:.4g} s); lower solver.time_step or "
      "solver.dt_safety",
      steps_, time_, i, (bodies_.velocity[i] * time_step_.dt).norm(), time_step_.dt,
      time_step_.stable);
}

Real Simulation::strain_energy() const {
  tell_ranks(RankCommand::StrainEnergy);
  Real strain = 0.0;
  for (const StepPart* p : ledger_order_) p->add_strain_energy(strain);
  return strain;
}

Energy Simulation::energy() const {
  Energy e = energy_;
  e.strain = strain_energy();
  return e;
}

Index Simulation::damaged_points() const {
  const ContactState& cs = concrete_.state();
  return cs.damaged_or_broken - cs.broken;
}

Index Simulation::broken_interface_points() const {
  Index n = 0;
  for (const auto& bar : interfaces_)
    for (const LocalPointRecord& r : bar->state().point.records) n += (r.history.damage >= 1.0);
  return n;
}

Index Simulation::yielded_nodes() const {
  Index n = 0;
  for (const auto& s : nodes_.states()) n += s.yielded;
  return n;
}

Real Simulation::max_axial_force() const {
  Real m = 0.0;
  for (const auto& s : nodes_.states()) m = std::max(m, std::abs(s.axial_force));
  return m;
}

Index Simulation::broken_points() const { return concrete_.state().broken; }

}  // namespace rcdem
