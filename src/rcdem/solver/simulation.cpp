#include "rcdem/solver/simulation.hpp"

#include <cmath>
#include <limits>

#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/parallel.hpp"

namespace rcdem {

Simulation::Simulation(const Scenario& sc, Specimen specimen)
    : specimen_(std::move(specimen)),
      bodies_(
          bodies_from_particles(specimen_.particles, sc.solver.density, sc.solver.mass_scaling)),
      law_kind_(sc.law),
      bilinear_{sc.contact.sigma_nt, sc.contact.tau, sc.contact.G_fn, sc.contact.G_fs,
                sc.contact.mu_c},
      damping_(sc.solver.damping) {
  contacts_.init(specimen_.contacts, bodies_.position);
  body_contacts_ = BodyContacts::build(specimen_.contacts, bodies_.size());
  plates_ = make_plates(sc.plates, specimen_.geometry);
  plate_contacts_ = make_plate_contacts(plates_, specimen_.boundary, bodies_, sc.contact);
  plate_force_prev_.assign(plates_.size(), 0.0);
  plate_displacement_prev_.assign(plates_.size(), 0.0);
  const auto n = static_cast<std::size_t>(bodies_.size());
  body_damping_work_.assign(n, 0.0);
  body_kinetic_.assign(n, 0.0);
  body_jumped_.assign(n, 0);
  compute_stable_time_step();
  dt_ = sc.solver.dt_safety * stable_dt_;
  if (sc.solver.time_step > 0.0) {
    if (sc.solver.time_step > 0.5 * stable_dt_)
      fail(
          "{}: key 'solver.time_step' ({:.4g} s) is above the stable limit: at most 0.5 x the "
          "critical estimate {:.4g} s = {:.4g} s",
          sc.source.string(), sc.solver.time_step, stable_dt_, 0.5 * stable_dt_);
    dt_ = sc.solver.time_step;
  }
}

void Simulation::compute_stable_time_step() {
  const ContactNetwork& net = specimen_.contacts;
  const auto n = static_cast<std::size_t>(bodies_.size());
  std::vector<Real> k(n, 0.0), kr(n, 0.0);
  for (Index c = 0; c < net.contact_count(); ++c) {
    const Index a = net.particle_a[c], b = net.particle_b[c];
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
      const Real kn = net.constants[m].kn;
      k[a] += kn;
      k[b] += kn;
      kr[a] += kn * (net.point_position0[m] - bodies_.position0[a]).squaredNorm();
      kr[b] += kn * (net.point_position0[m] - bodies_.position0[b]).squaredNorm();
    }
  }
  for (Index j = 0; j < plate_contacts_.size(); ++j) {
    const Index i = plate_contacts_.particle[j];
    const Real kn = plate_contacts_.constants[j].kn;
    k[i] += kn;
    kr[i] += kn * (plate_contacts_.point0[j] - bodies_.position0[i]).squaredNorm();
  }
  Real dt = std::numeric_limits<Real>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    if (k[i] > 0.0) dt = std::min(dt, std::sqrt(bodies_.mass[i] / k[i]));
    if (kr[i] > 0.0) dt = std::min(dt, std::sqrt(bodies_.inertia[i].minCoeff() / kr[i]));
  }
  if (!std::isfinite(dt)) fail("the specimen has no contact: no time step can be estimated");
  stable_dt_ = dt;
}

const Plate* Simulation::find_plate(const std::string& name) const {
  for (const auto& p : plates_)
    if (p.name == name) return &p;
  return nullptr;
}

void Simulation::step() {
  // 1. Contacts at the current positions (the law picked once for the whole loop).
  ContactNetwork& net = specimen_.contacts;
  if (law_kind_ == ConcreteLaw::BilinearSoftening)
    evaluate_contacts(bilinear_, net, bodies_, contacts_, dt_);
  else
    evaluate_contacts(elastic_, net, bodies_, contacts_, dt_);
  // 2. Plates.
  evaluate_plate_contacts(plates_, plate_contacts_, bodies_);
  // 3. Gather, 4. integrate.
  gather_forces();
  integrate();

  // Energy ledger (sums in a fixed order: deterministic).
  Real strain = 0.0, damage = 0.0, friction = 0.0;
  for (Index c = 0; c < net.contact_count(); ++c) {
    strain += contacts_.strain_energy[c];
    damage += contacts_.dissipated_damage[c];
    friction += contacts_.dissipated_friction[c];
  }
  for (Index j = 0; j < plate_contacts_.size(); ++j) {
    strain += plate_contacts_.strain_energy[j];
    friction += plate_contacts_.dissipated_friction[j];
  }
  Real damping_work = 0.0, kinetic = 0.0;
  for (std::size_t i = 0; i < body_kinetic_.size(); ++i) {
    damping_work += body_damping_work_[i];
    kinetic += body_kinetic_[i];
  }
  energy_.strain = strain;
  energy_.damage += damage;
  energy_.friction += friction;
  energy_.damping += damping_work;
  energy_.kinetic = 0.5 * (kinetic_half_ + kinetic);  // at the whole step
  kinetic_half_ = kinetic;

  // 5. Plates: work done over the last move (trapezoidal in the force), then the next move.
  for (std::size_t p = 0; p < plates_.size(); ++p) {
    Plate& plate = plates_[p];
    const Real f_on_specimen = -plate.force[plate.axis];
    const Real work = 0.5 * (plate_force_prev_[p] + f_on_specimen) *
                      (plate.displacement - plate_displacement_prev_[p]);
    plate.work += work;
    energy_.external_work += work;
    plate_force_prev_[p] = f_on_specimen;
    plate_displacement_prev_[p] = plate.displacement;
    plate.displacement += plate.velocity_at(time_ + 0.5 * dt_) * dt_;
  }
  time_ += dt_;
  ++steps_;
}

void Simulation::gather_forces() {
  const ContactState& cs = contacts_;
  parallel_for(bodies_.size(), [&](Index i) {
    Vec3 f = Vec3::Zero(), t = Vec3::Zero();
    for (Index e = body_contacts_.begin[i]; e < body_contacts_.begin[i + 1]; ++e) {
      const Index entry = body_contacts_.entry[e];
      const Index c = entry >> 1;
      if (entry & 1) {
        f += cs.force_b[c];
        t += cs.torque_b[c];
      } else {
        f -= cs.force_b[c];
        t += cs.torque_a[c];
      }
    }
    bodies_.force[i] = f;
    bodies_.torque[i] = t;
  });
  for (Index j = 0; j < plate_contacts_.size(); ++j) {
    const Index i = plate_contacts_.particle[j];
    bodies_.force[i] += plate_contacts_.force[j];
    bodies_.torque[i] += plate_contacts_.torque[j];
  }
}

void Simulation::integrate() {
  const Real dt = dt_;
  const Real alpha = damping_;
  Bodies& b = bodies_;
  parallel_for(b.size(), [&](Index i) {
    // Local non-viscous damping (Cundall): each component of the force is reduced by alpha |F|
    // against the velocity. Its work, on the mean of the old and new velocities, is the energy
    // damping removes (the leap-frog kinetic energy changes by exactly that mean).
    Real damping_work = 0.0;
    const Vec3 v_old = b.velocity[i];
    const Vec3 w_old = b.angular_velocity[i];
    Vec3 f = b.force[i], t = b.torque[i];
    Vec3 fd, td;
    for (int k = 0; k < 3; ++k) {
      fd[k] = alpha * std::abs(f[k]) * (v_old[k] > 0 ? 1.0 : v_old[k] < 0 ? -1.0 : 0.0);
      td[k] = alpha * std::abs(t[k]) * (w_old[k] > 0 ? 1.0 : w_old[k] < 0 ? -1.0 : 0.0);
    }
    const Vec3 v_new = v_old + (f - fd) * (dt / b.mass[i]);
    // Spheres: isotropic inertia, so the world-frame update is exact; cylinders (SPEC 7) will
    // need the full Euler equations.
    const Vec3 w_new = w_old + (t - td).cwiseQuotient(b.inertia[i]) * dt;
    damping_work += fd.dot(0.5 * (v_old + v_new)) * dt + td.dot(0.5 * (w_old + w_new)) * dt;
    b.velocity[i] = v_new;
    b.angular_velocity[i] = w_new;
    const Vec3 dx = v_new * dt;
    b.position[i] += dx;
    const Vec3 rot = w_new * dt;
    const Real angle = rot.norm();
    if (angle > 0.0) {
      b.orientation[i] = Quat(Eigen::AngleAxis<Real>(angle, rot / angle)) * b.orientation[i];
      b.orientation[i].normalize();
    }
    body_damping_work_[i] = damping_work;
    body_kinetic_[i] =
        0.5 * b.mass[i] * v_new.squaredNorm() + 0.5 * w_new.dot(b.inertia[i].cwiseProduct(w_new));
    // Instability: in a stable run nothing moves a twentieth of its size in one step.
    body_jumped_[i] = !(dx.norm() < 0.05 * b.radius[i]) || !(angle < 0.05);
  });
  for (Index i = 0; i < b.size(); ++i)
    if (body_jumped_[i])
      fail(
          "numerical instability at step {} (t = {:.6g} s): body {} moved {:.3g} m in one step "
          "(time step {:.4g} s, stable estimate {:.4g} s); lower solver.time_step or "
          "solver.dt_safety",
          steps_, time_, i, (b.velocity[i] * dt).norm(), dt_, stable_dt_);
}

Index Simulation::damaged_points() const {
  Index n = 0;
  for (const auto& s : contacts_.point) n += (s.damage > 0.0 && s.damage < 1.0);
  return n;
}

Index Simulation::broken_points() const {
  Index n = 0;
  for (const auto& s : contacts_.point) n += (s.damage >= 1.0);
  return n;
}

}  // namespace rcdem
