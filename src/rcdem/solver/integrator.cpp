#include "rcdem/solver/integrator.hpp"

#include "rcdem/core/parallel.hpp"
#include "rcdem/reinforcement/rigid_rotation.hpp"
#include "rcdem/solver/sphere_update.hpp"

namespace rcdem {

bool Integrator::advance(Bodies& b, const PrescribedMotion& motion, Real dt) {
  const Real alpha = damping_;
  const SphereStepOutputs out{sums_.damping_work.data(), sums_.kinetic.data(), sums_.jumped.data()};
  // Each block also sums its bodies' energies and flags (in body order) while they are in cache:
  // the step's ledger adds the blocks in order instead of passing over every body on one thread.
  const Index first = sphere_begin_, last = sphere_end_ < 0 ? sums_.spheres : sphere_end_;
  parallel_for_blocks(last - first, BodyStepSums::kSphereBlock, [&](Index from, Index to) {
    const Index begin = first + from, end = first + to;
    advance_spheres(b, begin, end, dt, alpha, out);
    BodyStepSums::Block s;
    for (Index i = begin; i < end; ++i) {
      s.damping_work += sums_.damping_work[i];
      s.kinetic += sums_.kinetic[i];
      s.jumped |= sums_.jumped[i];
    }
    sums_.blocks[static_cast<std::size_t>(begin / BodyStepSums::kSphereBlock)] = s;
  });
  for (Index i = sums_.spheres; i < b.size(); ++i) advance_cylinder(b, i, motion, dt);
  return jumped();
}

bool Integrator::jumped() const {
  bool any = false;
  for (const BodyStepSums::Block& s : sums_.blocks) any |= s.jumped != 0;
  for (std::size_t i = static_cast<std::size_t>(sums_.spheres); i < sums_.jumped.size(); ++i)
    any |= sums_.jumped[i] != 0;
  return any;
}

void Integrator::advance_cylinder(Bodies& b, Index i, const PrescribedMotion& motion, Real dt) {
  // Local non-viscous damping (Cundall): each component of the force is reduced by alpha |F|
  // against the velocity. Its work, on the mean of the old and new velocities, is the energy
  // damping removes (the leap-frog kinetic energy changes by exactly that mean).
  const Vec3 v_old = b.velocity[i];
  const Vec3 w_old = b.angular_velocity[i];
  const Vec3 f = b.force[i], t = b.torque[i];
  Vec3 fd, td;
  for (int k = 0; k < 3; ++k) {
    fd[k] = cundall_damping(damping_, f[k], v_old[k]);
    td[k] = cundall_damping(damping_, t[k], w_old[k]);
  }
  Vec3 v_new = v_old + (f - fd) * (dt / b.mass[i]);
  const std::int64_t slot = motion.slot[static_cast<std::size_t>(i)];
  if (slot >= 0) {
    // Prescribed: its velocity, rotation held, no damping.
    v_new = motion.velocity[static_cast<std::size_t>(slot)];
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
  const Vec3 w_new = advance_rotation(b.orientation[i], b.angular_momentum[i], b.inertia[i], t - td,
                                      dt, b.orientation0[i]);
  Real damping_work = 0.0;
  damping_work += fd.dot(0.5 * (v_old + v_new)) * dt + td.dot(0.5 * (w_old + w_new)) * dt;
  sums_.damping_work[i] = damping_work;
  b.velocity[i] = v_new;
  b.angular_velocity[i] = w_new;
  const Vec3 dx = v_new * dt;
  b.position[i] += dx;
  // The leap-frog's kinetic energy at the whole step, 1/2 m v(n-1/2).v(n+1/2) (and its rotational
  // analogue): the quantity it conserves with the strain energy. The mean of the two half-step
  // energies would oscillate by m |a dt|^2 / 4.
  sums_.kinetic[i] = 0.5 * b.mass[i] * v_old.dot(v_new) +
                     0.25 * (L_old.dot(w_new) + b.angular_momentum[i].dot(w_old));
  // Instability: in a stable run nothing moves a twentieth of its size in one step, nor turns
  // 0.05 rad (the turn is exp(w dt): its angle is |w| dt).
  const Real dx_limit = 0.05 * b.radius[i];
  sums_.jumped[i] = !(dx.squaredNorm() < dx_limit * dx_limit) ||
                    !(w_new.squaredNorm() * dt * dt < kStableTurnLimit * kStableTurnLimit);
}

Index Integrator::first_jumped() const {
  for (std::size_t i = 0; i < sums_.jumped.size(); ++i)
    if (sums_.jumped[i]) return static_cast<Index>(i);
  return -1;
}

void Integrator::add_energies(Real& damping_work, Real& kinetic) const {
  for (const BodyStepSums::Block& s : sums_.blocks) {
    damping_work += s.damping_work;
    kinetic += s.kinetic;
  }
  for (std::size_t i = static_cast<std::size_t>(sums_.spheres); i < sums_.kinetic.size(); ++i) {
    damping_work += sums_.damping_work[i];
    kinetic += sums_.kinetic[i];
  }
}

}  // namespace rcdem
