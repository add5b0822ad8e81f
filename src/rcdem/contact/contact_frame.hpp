#pragma once
// What the evaluation of a contact reads (the bodies' kinematics) and the frame it works in:
// shared by the loop over points (contact_loop.hpp) and the damaged contacts evaluated from sums
// (damaged_condensation.hpp).
#include <cmath>

#include "rcdem/contact/contact_kinematics.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// What the evaluation of a network's contacts reads in one step.
struct ContactInputs {
  const ContactNetwork& net;
  const Vec3* x;                    // body centres at the evaluation
  const Vec3* x0;                   // at t = 0
  const Vec3* w;                    // angular velocities
  const Quat* q0;                   // orientations at t = 0
  const Eigen::Matrix3d* rotation;  // orientations as matrices
  const Vec3* anchor0;              // interface contacts only (below), else null
  Real dt;
  const Real* pose = nullptr;  // BodyPoses of x and the orientations: needed with condensation
};

// With `anchor0` (steel-concrete interface contacts, SPEC 8), B is a cylinder and the normal is the
// component of (x_A - anchor) perpendicular to the cylinder's current axis, pointing from A to the
// axis, anchor being the interface sphere's centre carried by the cylinder: the sphere
// discretisation then adds no artificial interlock along the bar.
[[gnu::always_inline]] inline Vec3 contact_normal(const ContactInputs& in, Index a, Index b,
                                                  Index c) {
  if (in.anchor0) {
    const Eigen::Matrix3d& rb = in.rotation[b];
    const Vec3 axis = rb * (in.q0[b] * Vec3::UnitZ());
    const Vec3 anchor = in.x[b] + rb * (in.anchor0[c] - in.x0[b]);
    const Vec3 d = anchor - in.x[a];
    return (d - d.dot(axis) * axis).normalized();
  }
  // Eigen's normalized() of this expression was not inlined: a call per contact, 15% of the step.
  const Vec3 d = in.x[b] - in.x[a];
  return d / std::sqrt(d.squaredNorm());  // the same rounding as normalized()
}

// A contact's frame E = [n t1 t2] and the matrices its points need, in that frame:
//   relative displacement (SPEC 4, contact_kinematics.hpp): u_J = u0 + (R_B - R_A) r,
//     r = p_J0 - x_A0, so in the frame E^T u_J = E^T u0 + (E^T (R_B - R_A)) r;
//   the point's position relative to A's centre, x_A + R_A r + u_J / 2 - x_A, in the frame
//     rho = E^T u0 / 2 + (E^T (R_A + (R_B - R_A) / 2)) r.
struct ContactFrame {
  Vec3 n, t1, t2;
  Vec3 dx;               // x_B - x_A
  Eigen::Matrix3d disp;  // E^T (R_B - R_A)
  Eigen::Matrix3d arm;   // E^T (R_A + R_B) / 2
  Vec3 disp0;            // E^T u0
};

[[gnu::always_inline]] inline ContactFrame contact_frame(const ContactInputs& in, Index a, Index b,
                                                         const Vec3& n, const Vec3& t1) {
  ContactFrame f;
  f.n = n;
  f.t1 = t1;
  f.t2 = n.cross(t1);
  Eigen::Matrix3d frame_t;  // E^T: rows n, t1, t2
  frame_t.row(0) = n.transpose();
  frame_t.row(1) = t1.transpose();
  frame_t.row(2) = f.t2.transpose();
  const Eigen::Matrix3d& ra = in.rotation[a];
  const Eigen::Matrix3d& rb = in.rotation[b];
  f.dx = in.x[b] - in.x[a];
  const Vec3 r0 = in.x0[b] - in.x0[a];
  Vec3 u0;
  for (int i = 0; i < 3; ++i)
    u0[i] = offset_displacement(f.dx[i], rb(i, 0), rb(i, 1), rb(i, 2), r0.x(), r0.y(), r0.z());
  f.disp = frame_t * (rb - ra);
  f.disp0 = frame_t * u0;
  f.arm = frame_t * (0.5 * (ra + rb));
  return f;
}

// SPEC 4: the plane's frame turns with the contact, carrying every point's shear history. The
// first axis t1 at this evaluation, from the one stored at the last.
[[gnu::always_inline]] inline Vec3 turned_frame_axis(const ContactInputs& in,
                                                     const ContactState& cs, Index a, Index b,
                                                     Index c, const Vec3& n) {
  const PlaneRotation rot{cs.normal[c], n, 0.5 * in.dt * (in.w[a] + in.w[b]).dot(n)};
  const Vec3 t1 = rot.turn_frame_axis(cs.tangent[c]);
  return t1.squaredNorm() > 0.5 ? t1 : any_perpendicular(n);  // only after a turn near 90 deg
}

// What a contact's points add up to, in its frame.
struct PointTotals {
  Real phi_n = 0, phi_1 = 0, phi_2 = 0, mom_n = 0, mom_1 = 0, mom_2 = 0;
  Real damage = 0, friction = 0, max_damage = 0, outside = 0;
};

// Writes contact c's force on B, torques and dissipation from its totals in frame f:
//   the force on B is E phi; the moment about A is sum (E rho) x (E phi) = E mom (E is a
//   rotation), and about B it is that less dx x f.
[[gnu::always_inline]] inline void store_contact(ContactState& cs, Index c, const ContactFrame& f,
                                                 const PointTotals& t) {
  const Vec3 force = t.phi_n * f.n + t.phi_1 * f.t1 + t.phi_2 * f.t2;
  const Vec3 moment_a = t.mom_n * f.n + t.mom_1 * f.t1 + t.mom_2 * f.t2;
  cs.force_b[c] = force;
  cs.torque_b[c] = moment_a - f.dx.cross(force);
  cs.torque_a[c] = -moment_a;
  cs.dissipated_damage[c] = t.damage;
  cs.dissipated_friction[c] = t.friction;
}

}  // namespace rcdem
