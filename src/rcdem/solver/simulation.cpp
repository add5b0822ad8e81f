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
      concrete_(ConcreteContacts::build(sc, specimen_.contacts, bodies_)),
      bars_(BarSystem::build(sc, specimen_, bodies_)),
      pulled_(PulledBars::build(sc, specimen_, bodies_.size())),
      plates_(
          PlateSet::build(sc.plates, specimen_.geometry, specimen_.boundary, bodies_, sc.contact)),
      step_sums_(BodyStepSums::build(bodies_, pulled_.driven)),
      damping_(sc.solver.damping),
      loading_rate_(sc.loading_rate) {
  // The small networks' tasks: a few dozen items each (about 10-30 us of work at most).
  const auto add_tasks = [this](SmallTask::Kind kind, std::size_t bar, Index count, Index size) {
    for (Index begin = 0; begin < count; begin += size)
      small_tasks_.push_back({kind, bar, begin, std::min(count, begin + size)});
  };
  for (std::size_t k = 0; k < specimen_.interfaces.size(); ++k)
    add_tasks(SmallTask::kInterface, k, specimen_.interfaces[k].net.contact_count(), 64);
  add_tasks(SmallTask::kPlates, 0, plates_.contacts.size(), 256);
  add_tasks(SmallTask::kNodes, 0, static_cast<Index>(bars_.nodes.size()), 64);
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

template <class Visitor>
void Simulation::visit_springs(Visitor&& v) const {
  const auto unit = [](const Vec3& d) { return Vec3(d / d.norm()); };
  const ContactNetwork& nw = specimen_.contacts;
  std::vector<Vec3> normal(static_cast<std::size_t>(nw.contact_count()));
  for (Index c = 0; c < nw.contact_count(); ++c)
    normal[c] = unit(bodies_.position0[nw.particle_b[c]] - bodies_.position0[nw.particle_a[c]]);
  v.network(nw, std::move(normal));
  // Interface contacts: normal across the cylinder's axis through the interface sphere.
  for (const auto& ic : specimen_.interfaces) {
    std::vector<Vec3> n(static_cast<std::size_t>(ic.net.contact_count()));
    for (Index c = 0; c < ic.net.contact_count(); ++c) {
      const Vec3 axis = bodies_.orientation0[ic.net.particle_b[c]] * Vec3::UnitZ();
      const Vec3 d = bodies_.position0[ic.net.particle_a[c]] - ic.anchor0[c];
      n[c] = unit(d - d.dot(axis) * axis);
    }
    v.network(ic.net, std::move(n));
  }
  // Every plate contact, closed or not: the stiffest the plates can make the assembly.
  for (Index j = 0; j < plates_.contacts.size(); ++j) {
    const Index i = plates_.contacts.particle[j];
    const LocalPointConstants& k = plates_.contacts.constants[j];
    const Vec3 arm = plates_.contacts.point0[j] - bodies_.position0[i];
    v.spring(-1, i, arm, arm, plates_.plates[plates_.contacts.plate[j]].normal, k.kn, k.ks);
  }
  // Interaction nodes (9): k_a along the node's axis and k_t across it, at the node; k_b and
  // k_theta as rotational springs. The node's vectors are world vectors at t = 0.
  for (std::size_t j = 0; j < bars_.nodes.size(); ++j) {
    const InteractionNode& node = bars_.nodes[j];
    const Vec3 axis = unit(node.axis_a + node.axis_b);
    const Mat3 kr = node.k.bending * (Mat3::Identity() - axis * axis.transpose()) +
                    node.k.torsion * axis * axis.transpose();
    const NodeRef& r = bars_.node_refs[j];
    v.spring(r.body_a, r.body_b, node.arm_a, node.arm_b, axis, node.k.axial, node.k.shear);
    v.rotational(r.body_a, r.body_b, kr);
  }
}

namespace {
// visit_springs() into the bodies' own blocks: each spring counts on each of its bodies.
struct BlockVisitor {
  BodyStiffness& blocks;
  const std::vector<Vec3>& centre0;
  void network(const ContactNetwork& nw, const std::vector<Vec3>& normal) {
    for (Index c = 0; c < nw.contact_count(); ++c) {
      const Index a = nw.particle_a[c], b = nw.particle_b[c];
      for (Index m = nw.point_begin[c]; m < nw.point_begin[c + 1]; ++m) {
        const LocalPointConstants& k = nw.constants[m];
        blocks.add_spring(a, normal[c], k.kn, k.ks, nw.point_position0[m] - centre0[a]);
        blocks.add_spring(b, normal[c], k.kn, k.ks, nw.point_position0[m] - centre0[b]);
      }
    }
  }
  void spring(Index a, Index b, const Vec3& arm_a, const Vec3& arm_b, const Vec3& n, Real kn,
              Real ks) {
    if (a >= 0) blocks.add_spring(a, n, kn, ks, arm_a);
    blocks.add_spring(b, n, kn, ks, arm_b);
  }
  void rotational(Index a, Index b, const Mat3& k) {
    blocks.add_rotational(a, k);
    blocks.add_rotational(b, k);
  }
};

// visit_springs() into the assembly's operator.
struct AssemblyVisitor {
  AssembledStiffness& k;
  void network(const ContactNetwork& nw, std::vector<Vec3> normal) {
    k.add_network(nw, std::move(normal));
  }
  void spring(Index a, Index b, const Vec3& arm_a, const Vec3& arm_b, const Vec3& n, Real kn,
              Real ks) {
    k.add_spring(a, b, arm_a, arm_b, n, kn, ks);
  }
  void rotational(Index a, Index b, const Mat3& kr) { k.add_rotational(a, b, kr); }
};
}  // namespace

void Simulation::compute_stable_time_step(Real added_mass_limit, TimeStepEstimate estimate,
                                          const std::string& source) {
  // SPEC 6's sqrt(m / sum k) per body, with "sum k" the body's own 6x6 stiffness block
  // (solver/body_stiffness.hpp: why a block, and what the safety factor covers).
  BodyStiffness blocks(bodies_.size());
  visit_springs(BlockVisitor{blocks, bodies_.position0});
  // Each body's own estimate, and the body and motion that set the shortest (named below).
  std::vector<Real> steps(static_cast<std::size_t>(bodies_.size()));
  Index first = 0;
  BodyStiffness::Limit l{std::numeric_limits<Real>::infinity(), false, 0};
  for (Index i = 0; i < bodies_.size(); ++i) {
    const BodyStiffness::Limit li = blocks.limit(i, bodies_.mass[i], bodies_.inertia[i],
                                                 bodies_.orientation0[i].toRotationMatrix());
    steps[static_cast<std::size_t>(i)] = li.time_step;
    if (li.time_step < l.time_step) {
      l = li;
      first = i;
    }
  }
  if (!std::isfinite(l.time_step))
    fail("the specimen has no contact: no time step can be estimated");
  const bool cylinder = first >= specimen_.concrete();
  static const char* const kWhat[] = {"rotation about body axis x", "rotation about body axis y",
                                      "rotation about body axis z"};
  static const char* const kCylinder[] = {"bending rotation", "bending rotation", "torsion"};
  time_step_.limit = fmt::format("{} {} ({})", cylinder ? "bar cylinder" : "particle", first,
                                 !l.rotation ? "translation"
                                 : cylinder  ? kCylinder[l.body_axis]
                                             : kWhat[l.body_axis]);
  // Issue 28: a step this short means a stiffness or mass far outside any material (a run would
  // need 1e12 steps per second of loading, or fill its history with inf): refused, naming why.
  if (!(l.time_step >= kMinimumTimeStep))
    fail(
        "{}: the stable time step {:.3g} s, set by {}, is below {:.0e} s: it is far too stiff "
        "for its mass; check contact.E_bar, bars.*.E, material.density and bars.*.density",
        source, l.time_step, time_step_.limit, kMinimumTimeStep);
  // Selective mass scaling (solver/selective_mass_scaling.hpp): the bodies below a common target
  // made heavier, mass and inertia alike, which lifts each one's estimate to the target exactly.
  time_step_.mass_scaling = plan_selective_mass_scaling(steps, bodies_.mass, added_mass_limit);
  for (Index i = 0; i < bodies_.size(); ++i) {
    const Real f = time_step_.mass_scaling.factor[static_cast<std::size_t>(i)];
    bodies_.mass[i] *= f;
    bodies_.inertia[i] *= f;
  }
  if (time_step_.mass_scaling.bodies_scaled > 0)
    time_step_.limit = fmt::format(
        "selective mass scaling: {} bodies up to {:.3f}x heavier, +{:.3g}% mass; unscaled {:.4g} "
        "s, set by {}",
        time_step_.mass_scaling.bodies_scaled, time_step_.mass_scaling.largest_factor,
        100.0 * time_step_.mass_scaling.added_fraction(), time_step_.mass_scaling.unscaled_step,
        time_step_.limit);
  time_step_.stable = time_step_.mass_scaling.time_step;
  if (estimate == TimeStepEstimate::Assembled) {
    // The whole assembly's critical step, with the masses as scaled (critical_time_step.hpp).
    AssembledStiffness k(bodies_);
    visit_springs(AssemblyVisitor{k});
    time_step_.critical =
        assembled_critical_time_step(k, 1.0 / (time_step_.stable * time_step_.stable));
    time_step_.limit =
        fmt::format("{}, x 1/sqrt(1 + damping {}); per-body estimate {:.4g} s ({})",
                    time_step_.critical.how(), damping_, time_step_.stable, time_step_.limit);
    time_step_.stable = damped_critical_time_step(time_step_.critical.time_step, damping_);
  }
}

ContactInputs Simulation::concrete_inputs(const std::vector<Vec3>& positions,
                                          const std::vector<Eigen::Matrix3d>& rotation) const {
  return {specimen_.contacts,
          positions.data(),
          bodies_.position0.data(),
          bodies_.angular_velocity.data(),
          bodies_.orientation0.data(),
          rotation.data(),
          nullptr,
          time_step_.dt};
}

void Simulation::catch_up_condensed_points() const {
  // The last evaluation's kinematics: its centres and orientation matrices, both kept until the
  // next step forms them anew.
  if (!concrete_.condensation.any_condensed) return;
  catch_up_condensed(concrete_.law, concrete_inputs(concrete_.position_eval, concrete_.rotation),
                     concrete_.contacts, concrete_.condensation);
}

const PulledBar* Simulation::find_pulled_bar(const std::string& name) const {
  return pulled_.find(name);
}

const Plate* Simulation::find_plate(const std::string& name) const { return plates_.find(name); }

void Simulation::step() {
  // 1. Contacts at the current positions (the law picked once for the whole loop).
  ContactNetwork& net = specimen_.contacts;
  // The last evaluation's kinematics stay at hand: a contact condensed then and visited now first
  // has its points brought up to that step (contact_loop.hpp, evaluate_contacts).
  std::swap(concrete_.rotation, concrete_.rotation_prev);
  std::swap(concrete_.position_eval, concrete_.position_prev);
  parallel_for(bodies_.size(), [&](Index i) {
    concrete_.rotation[i] = bodies_.orientation[i].toRotationMatrix();
    concrete_.position_eval[i] = bodies_.position[i];
    concrete_.pose.set(i, bodies_.position[i], bodies_.orientation[i]);
  });
  // Evaluated from the copy, so that what a later catch-up reads is what this evaluation used.
  ContactInputs concrete = concrete_inputs(concrete_.position_eval, concrete_.rotation);
  concrete.pose = concrete_.pose.ptr();
  const ContactInputs previous = concrete_inputs(concrete_.position_prev, concrete_.rotation_prev);
  ElasticCondensation* condensed =
      concrete_.condensation.sums.empty() ? nullptr : &concrete_.condensation;
  evaluate_contacts(concrete_.law, concrete, concrete_.contacts, condensed, &previous);
  // Steel-concrete interfaces (each bar with its law), interaction nodes, 2. plates.
  parallel_tasks(static_cast<Index>(small_tasks_.size()),
                 [&](Index j) { run_small_task(small_tasks_[static_cast<std::size_t>(j)]); });
  sum_plate_reactions(plates_.plates, plates_.contacts);
  // 3. Gather, 4. integrate.
  gather_forces();
  integrate();

  // Energy ledger: what this step dissipated (sums in a fixed order: deterministic).
  Real damage = 0.0, friction = 0.0;
  if (!concrete_.contacts.block_damage.empty()) {  // the blocked loop summed its blocks
    for (std::size_t k = 0; k < concrete_.contacts.block_damage.size(); ++k) {
      damage += concrete_.contacts.block_damage[k];
      friction += concrete_.contacts.block_friction[k];
    }
  } else {
    for (Index c = 0; c < net.contact_count(); ++c) {
      damage += concrete_.contacts.dissipated_damage[c];
      friction += concrete_.contacts.dissipated_friction[c];
    }
  }
  for (Index j = 0; j < plates_.contacts.size(); ++j)
    friction += plates_.contacts.dissipated_friction[j];
  for (const auto& st : bars_.interface_states)
    for (std::size_t c = 0; c < st.dissipated_damage.size(); ++c) {
      damage += st.dissipated_damage[c];
      friction += st.dissipated_friction[c];
    }
  Real plastic = 0.0;
  for (std::size_t j = 0; j < bars_.nodes.size(); ++j) plastic += bars_.node_forces[j].dissipated;
  energy_.plastic += plastic;
  Real damping_work = 0.0, kinetic = 0.0;
  for (const BodyStepSums::Block& s : step_sums_.blocks) {
    damping_work += s.damping_work;
    kinetic += s.kinetic;
  }
  for (std::size_t i = static_cast<std::size_t>(step_sums_.spheres); i < step_sums_.kinetic.size();
       ++i) {
    damping_work += step_sums_.damping_work[i];
    kinetic += step_sums_.kinetic[i];
  }
  energy_.damage += damage;
  energy_.friction += friction;
  energy_.damping += damping_work;
  energy_.kinetic = kinetic;

  // Pulled bars: the driver's work over the last move (trapezoidal in its force).
  for (std::size_t k = 0; k < pulled_.bars.size(); ++k) {
    PulledBar& pb = pulled_.bars[k];
    pb.force = bodies_.force[pb.body];
    const Real f_driver = pb.load();
    const Real work = 0.5 * (pulled_.force_prev[k] + f_driver) * pb.last_step;
    pb.work += work;
    energy_.external_work += work;
    pulled_.force_prev[k] = f_driver;
    pb.last_step = bodies_.velocity[pb.body].dot(pb.direction) * time_step_.dt;
    pb.displacement += pb.last_step;
  }
  // 5. Plates: work done over the last move (trapezoidal in the force), then the next move.
  for (std::size_t p = 0; p < plates_.plates.size(); ++p) {
    Plate& plate = plates_.plates[p];
    const Real f_on_specimen = -plate.force[plate.axis];
    const Real work = 0.5 * (plates_.force_prev[p] + f_on_specimen) *
                      (plate.displacement - plates_.displacement_prev[p]);
    plate.work += work;
    energy_.external_work += work;
    plates_.force_prev[p] = f_on_specimen;
    plates_.displacement_prev[p] = plate.displacement;
    plate.displacement +=
        loading_rate_.factor() * plate.velocity_at(time_ + 0.5 * time_step_.dt) * time_step_.dt;
  }
  time_ += time_step_.dt;
  ++steps_;
  loading_rate_.update(steps_, time_step_.dt, energy_);
}

void Simulation::run_small_task(const SmallTask& task) {
  switch (task.kind) {
    case SmallTask::kInterface: {
      const InterfaceContacts& ic = specimen_.interfaces[task.bar];
      const ContactInputs in =
          body_inputs(ic.net, bodies_, concrete_.rotation.data(), ic.anchor0.data(), time_step_.dt);
      ContactState& st = bars_.interface_states[task.bar];
      evaluate_contact_range(bars_.interface_law[task.bar], in, st, task.begin, task.end);
      break;
    }
    case SmallTask::kPlates:
      for (Index k = task.begin; k < task.end; ++k)
        evaluate_plate_contact(plates_.plates, plates_.contacts, bodies_, k);
      break;
    case SmallTask::kNodes:
      for (Index j = task.begin; j < task.end; ++j) {
        const NodeRef& r = bars_.node_refs[static_cast<std::size_t>(j)];
        bars_.node_forces[static_cast<std::size_t>(j)] =
            evaluate_node(bars_.nodes[static_cast<std::size_t>(j)],
                          bars_.node_states[static_cast<std::size_t>(j)],
                          bodies_.position[r.body_a], bodies_.orientation[r.body_a],
                          bodies_.position[r.body_b], bodies_.orientation[r.body_b]);
      }
      break;
  }
}

void Simulation::gather_forces() {
  const ContactState& cs = concrete_.contacts;
  const BodyContacts& bc = concrete_.body_contacts;
  const Index bodies = bodies_.size();
  parallel_for(bodies, [&](Index i) {
    // A body's B-side contacts belong to particles before it along the curve, some far before:
    // their forces are no longer in cache, and waiting on them was most of the gather. Requested
    // a few bodies ahead, they arrive while it sums (measured in bench/RESULTS.md). The A side
    // streams in contact order.
    constexpr Index kAhead = 6;
    if (i + kAhead < bodies)
      for (Index e = bc.begin[i + kAhead]; e < bc.mid[i + kAhead]; ++e) {
        __builtin_prefetch(cs.force_b[bc.entry[e]].data());
        __builtin_prefetch(cs.torque_b[bc.entry[e]].data());
      }
    Vec3 f = Vec3::Zero(), t = Vec3::Zero();
    for (Index e = bc.begin[i]; e < bc.mid[i]; ++e) {
      const Index c = bc.entry[e];
      f += cs.force_b[c];
      t += cs.torque_b[c];
    }
    for (Index e = bc.mid[i]; e < bc.begin[i + 1]; ++e) {
      const Index c = bc.entry[e];
      f -= cs.force_b[c];
      t += cs.torque_a[c];
    }
    bodies_.force[i] = f;
    bodies_.torque[i] = t;
  });
  // The few interface contacts, nodes and plate contacts: serial, in a fixed order.
  for (std::size_t k = 0; k < bars_.interface_states.size(); ++k) {
    const ContactNetwork& nw = specimen_.interfaces[k].net;
    const ContactState& st = bars_.interface_states[k];
    for (Index c = 0; c < nw.contact_count(); ++c) {
      bodies_.force[nw.particle_b[c]] += st.force_b[c];
      bodies_.torque[nw.particle_b[c]] += st.torque_b[c];
      bodies_.force[nw.particle_a[c]] -= st.force_b[c];
      bodies_.torque[nw.particle_a[c]] += st.torque_a[c];
    }
  }
  for (std::size_t j = 0; j < bars_.nodes.size(); ++j) {
    const NodeRef& r = bars_.node_refs[j];
    bodies_.force[r.body_a] += bars_.node_forces[j].force_a;
    bodies_.torque[r.body_a] += bars_.node_forces[j].torque_a;
    bodies_.force[r.body_b] += bars_.node_forces[j].force_b;
    bodies_.torque[r.body_b] += bars_.node_forces[j].torque_b;
  }
  for (Index j = 0; j < plates_.contacts.size(); ++j) {
    const Index i = plates_.contacts.particle[j];
    bodies_.force[i] += plates_.contacts.force[j];
    bodies_.torque[i] += plates_.contacts.torque[j];
  }
}

void Simulation::integrate() {
  const Real dt = time_step_.dt;
  const Real alpha = damping_;
  Bodies& b = bodies_;
  // The concrete particles in SIMD lanes (sphere_update.hpp), then the cylinders.
  const SphereStepOutputs out{step_sums_.damping_work.data(), step_sums_.kinetic.data(),
                              step_sums_.jumped.data()};
  // Each block also sums its bodies' energies and flags (in body order) while they are in cache:
  // the step's ledger adds the blocks in order instead of passing over every body on one thread.
  parallel_for_blocks(step_sums_.spheres, BodyStepSums::kSphereBlock, [&](Index begin, Index end) {
    advance_spheres(b, begin, end, dt, alpha, out);
    BodyStepSums::Block s;
    for (Index i = begin; i < end; ++i) {
      s.damping_work += step_sums_.damping_work[i];
      s.kinetic += step_sums_.kinetic[i];
      s.jumped |= step_sums_.jumped[i];
    }
    step_sums_.blocks[static_cast<std::size_t>(begin / BodyStepSums::kSphereBlock)] = s;
  });
  for (Index i = step_sums_.spheres; i < b.size(); ++i) {
    // Local non-viscous damping (Cundall): each component of the force is reduced by alpha |F|
    // against the velocity. Its work, on the mean of the old and new velocities, is the energy
    // damping removes (the leap-frog kinetic energy changes by exactly that mean).
    Real damping_work = 0.0;
    const Vec3 v_old = b.velocity[i];
    const Vec3 w_old = b.angular_velocity[i];
    Vec3 f = b.force[i], t = b.torque[i];
    Vec3 fd, td;
    for (int k = 0; k < 3; ++k) {
      fd[k] = cundall_damping(alpha, f[k], v_old[k]);
      td[k] = cundall_damping(alpha, t[k], w_old[k]);
    }
    Vec3 v_new = v_old + (f - fd) * (dt / b.mass[i]);
    const std::int64_t driven = pulled_.driven[static_cast<std::size_t>(i)];
    if (driven >= 0) {
      // A pulled cylinder: prescribed velocity, rotation held, no damping.
      const PulledBar& pb = pulled_.bars[static_cast<std::size_t>(driven)];
      v_new = loading_rate_.factor() * pb.velocity_at(time_ + 0.5 * dt) * pb.direction;
      fd.setZero();
      td = t;
      b.angular_momentum[i].setZero();
    }
    // Rotation: the angular momentum takes the torque and the orientation follows by the
    // rotational leap-frog (rigid_rotation.hpp): exact for isotropic inertia, second order for
    // the cylinders'. Spheres keep the angular velocity as their state (L = I w, so a caller may
    // set w); cylinders keep the angular momentum.
    if (b.inertia[i].x() == b.inertia[i].z()) b.angular_momentum[i] = b.inertia[i].x() * w_old;
    const Vec3 L_old = b.angular_momentum[i];
    const Vec3 w_new = advance_rotation(b.orientation[i], b.angular_momentum[i], b.inertia[i],
                                        t - td, dt, b.orientation0[i]);
    damping_work += fd.dot(0.5 * (v_old + v_new)) * dt + td.dot(0.5 * (w_old + w_new)) * dt;
    b.velocity[i] = v_new;
    b.angular_velocity[i] = w_new;
    const Vec3 dx = v_new * dt;
    b.position[i] += dx;
    step_sums_.damping_work[i] = damping_work;
    // The leap-frog's kinetic energy at the whole step, 1/2 m v(n-1/2).v(n+1/2) (and its rotational
    // analogue): the quantity it conserves with the strain energy. The mean of the two half-step
    // energies would oscillate by m |a dt|^2 / 4.
    step_sums_.kinetic[i] = 0.5 * b.mass[i] * v_old.dot(v_new) +
                            0.25 * (L_old.dot(w_new) + b.angular_momentum[i].dot(w_old));
    // Instability: in a stable run nothing moves a twentieth of its size in one step, nor turns
    // 0.05 rad (the turn is exp(w dt): its angle is |w| dt).
    const Real dx_limit = 0.05 * b.radius[i];
    step_sums_.jumped[i] = !(dx.squaredNorm() < dx_limit * dx_limit) ||
                           !(w_new.squaredNorm() * dt * dt < kStableTurnLimit * kStableTurnLimit);
  }
  bool jumped = false;
  for (const BodyStepSums::Block& s : step_sums_.blocks) jumped |= s.jumped != 0;
  for (Index i = step_sums_.spheres; i < b.size(); ++i) jumped |= step_sums_.jumped[i] != 0;
  if (!jumped) return;
  for (Index i = 0; i < b.size(); ++i)
    if (step_sums_.jumped[i])
      fail(
          "numerical instability at step {} (t = {:.6g} s): body {} moved {:.3g} m in one step "
          "(time step {:.4g} s, stable estimate {:.4g} s); lower solver.time_step or "
          "solver.dt_safety",
          steps_, time_, i, (b.velocity[i] * dt).norm(), time_step_.dt, time_step_.stable);
}

namespace {
// The elastic energy held by a network's local points (SPEC 11), summed in a fixed order.
Real points_strain_energy(const ContactLaw& law, const ContactNetwork& net,
                          const ContactState& cs) {
  return std::visit(
      [&](const auto& l) {
        Real e = 0.0;
        for (Index c = 0; c < net.contact_count(); ++c) e += cs.strain_energy(l, net, c);
        return e;
      },
      law);
}
}  // namespace

Real Simulation::concrete_strain_energy() const {
  // By fixed blocks of contacts on every thread, then the blocks' sums in order: the same value
  // at any thread count. A history row asks for it every few dozen steps, and serial it costs
  // about a whole step of a cracked beam (bench/RESULTS.md).
  const ContactNetwork& net = specimen_.contacts;
  const bool condensed = concrete_.condensation.any_condensed;
  constexpr Index kBlock = 1024;
  const Index n = net.contact_count();
  concrete_.strain_energy_blocks.assign(static_cast<std::size_t>((n + kBlock - 1) / kBlock), 0.0);
  std::visit(
      [&](const auto& law) {
        parallel_for_blocks(n, kBlock, [&](Index begin, Index end) {
          // Condensed contacts from their sums at the last evaluation's kinematics (their
          // histories are stale), the others from their points.
          Real e = 0.0;
          for (Index c = begin; c < end; ++c) {
            const Index a = net.particle_a[c], b = net.particle_b[c];
            e += condensed && concrete_.condensation.condensed[static_cast<std::size_t>(c)]
                     ? condensed_strain_energy(
                           concrete_.condensation.sums, c, concrete_.position_eval[a],
                           concrete_.position_eval[b], concrete_.rotation[a], concrete_.rotation[b])
                     : concrete_.contacts.strain_energy(law, net, c);
          }
          concrete_.strain_energy_blocks[static_cast<std::size_t>(begin / kBlock)] = e;
        });
      },
      concrete_.law);
  Real e = 0.0;
  for (const Real block : concrete_.strain_energy_blocks) e += block;
  return e;
}

Real Simulation::strain_energy() const {
  Real strain = concrete_strain_energy();
  for (Index j = 0; j < plates_.contacts.size(); ++j) strain += plates_.contacts.strain_energy[j];
  for (std::size_t k = 0; k < bars_.interface_states.size(); ++k)
    strain += points_strain_energy(bars_.interface_law[k], specimen_.interfaces[k].net,
                                   bars_.interface_states[k]);
  for (std::size_t j = 0; j < bars_.nodes.size(); ++j)
    strain += node_elastic_energy(bars_.nodes[j], bars_.node_states[j]);
  return strain;
}

Energy Simulation::energy() const {
  Energy e = energy_;
  e.strain = strain_energy();
  return e;
}

Index Simulation::damaged_points() const {
  Index n = 0;
  for (const LocalPointRecord& r : concrete_.contacts.point.records)
    n += (r.history.damage > 0.0 && r.history.damage < 1.0);
  return n;
}

Index Simulation::broken_interface_points() const {
  Index n = 0;
  for (const auto& st : bars_.interface_states)
    for (const LocalPointRecord& r : st.point.records) n += (r.history.damage >= 1.0);
  return n;
}

Index Simulation::yielded_nodes() const {
  Index n = 0;
  for (const auto& s : bars_.node_states) n += s.yielded;
  return n;
}

Real Simulation::max_axial_force() const {
  Real m = 0.0;
  for (const auto& s : bars_.node_states) m = std::max(m, std::abs(s.axial_force));
  return m;
}

Index Simulation::broken_points() const {
  Index n = 0;
  for (const LocalPointRecord& r : concrete_.contacts.point.records) n += (r.history.damage >= 1.0);
  return n;
}

}  // namespace rcdem
