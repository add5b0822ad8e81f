#pragma once
// Rotation of one rigid body with non-isotropic inertia over one leap-frog step (SPEC 6; the
// cylinders of a bar, SPEC 7, whose axial and transverse moments differ).
//
// Scheme: the rotational leap-frog with the angular momentum L in the world frame at half steps
// (D. Fincham, "Leapfrog rotational algorithms", Molecular Simulation 8 (1992) 165-178),
//   L(n+1/2) = L(n-1/2) + T(n) dt,
// with the orientation advanced by the implicit midpoint rule on the rotation group:
//   q(n+1) = exp(w dt) q(n),   w = R_m I^-1 R_m^T L(n+1/2),   q_m = exp(w dt / 2) q(n),
// R_m the principal axes at the mid-step orientation q_m. Since q_m depends on w, w is found by
// fixed-point iteration, as in Omelyan's self-consistent rotational leap-frog (I. P. Omelyan,
// Computers in Physics 12 (1998) 97-103), which uses the Cayley form of the update where this
// uses the exact exponential. Why this one:
//   - it is second order and time-reversible: q_m is also exp(-w dt/2) q(n+1), so a step taken
//     back from q(n+1) with -L retraces this one; as a symmetric method for a reversible system
//     its energy error stays bounded (no drift), and L is conserved exactly without torque;
//   - with isotropic inertia w = L/I whatever the orientation, so the step is exactly the
//     spheres' w += T/I dt, q <- exp(w dt) q, and spheres and cylinders share one integrator.
// The returned w is the angular velocity of the step (constant over it): it is what the
// leap-frog calls the half-step angular velocity, for the kinematics, damping and kinetic energy
// (1/2 L.w).
#include <Eigen/Geometry>

#include "rcdem/core/small_angle.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

// exp of a rotation vector: the rotation by |rot| about rot, q = (cos h, sin h rot / |rot|) with
// h = |rot| / 2. A body turns ~1e-6 rad in a step: there cos h and sin h / h come from their series
// (core/small_angle.hpp), from h^2 alone (libm's sincos and the normalisation were a tenth of the
// bodies' update).
[[gnu::always_inline]] inline Quat rotation_exp(const Vec3& rot) {
  const Real h2 = 0.25 * rot.squaredNorm();
  if (is_small_angle(h2)) {
    Real c, sinc;
    small_angle_cos_sinc(h2, c, sinc);
    const Real s_over_angle = 0.5 * sinc;  // sin h / |rot|
    return Quat(c, s_over_angle * rot.x(), s_over_angle * rot.y(), s_over_angle * rot.z());
  }
  const Real angle = rot.norm();
  if (!(angle > 0.0)) return Quat::Identity();
  return Quat(Eigen::AngleAxis<Real>(angle, rot / angle));
}

// w = R I^-1 R^T L for a body whose principal axes are turned by `orientation * principal_axes0`
// (principal_axes0: the principal frame at the reference orientation; identity when the
// orientation itself maps the principal frame to the world).
[[gnu::always_inline]] inline Vec3 angular_velocity(
    const Quat& orientation, const Vec3& angular_momentum, const Vec3& principal_inertia,
    const Quat& principal_axes0 = Quat::Identity()) {
  const Quat axes = orientation * principal_axes0;
  return axes * (axes.conjugate() * angular_momentum).cwiseQuotient(principal_inertia);
}

// One step: L += T dt, then q <- exp(w dt) q with w from the self-consistent mid-step
// orientation. Returns w. `orientation` and `principal_axes0` as in angular_velocity().
inline Vec3 advance_rotation(Quat& orientation, Vec3& angular_momentum,
                             const Vec3& principal_inertia, const Vec3& torque, Real dt,
                             const Quat& principal_axes0 = Quat::Identity()) {
  angular_momentum += torque * dt;
  Vec3 w;
  if (principal_inertia.x() == principal_inertia.y() &&
      principal_inertia.y() == principal_inertia.z()) {
    w = angular_momentum / principal_inertia.x();
  } else {
    const Quat axes = orientation * principal_axes0;
    w = angular_velocity(axes, angular_momentum, principal_inertia);
    // Contraction factor ~ |w| dt / 2 x (inertia anisotropy): a handful of passes at stable
    // time steps; the cap only guards against a runaway step, which the solver reports anyway.
    for (int pass = 0; pass < 32; ++pass) {
      const Vec3 next =
          angular_velocity(rotation_exp(0.5 * dt * w) * axes, angular_momentum, principal_inertia);
      const Real change2 = (next - w).squaredNorm();
      w = next;
      if (change2 <= 1e-28 * w.squaredNorm()) break;  // the next pass would move w far less
    }
  }
  orientation = rotation_exp(w * dt) * orientation;
  orientation.normalize();
  return w;
}

}  // namespace rcdem
