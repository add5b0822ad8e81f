#pragma once
// The loop over contacts and their local points, written once for every law (the law is a
// template parameter, chosen once per step). Each contact writes only its own outputs, so the
// loop runs in parallel and the result does not depend on the thread count.
#include "rcdem/contact/contact_kinematics.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/core/parallel.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// With `anchor0` (steel-concrete interface contacts, SPEC 8), B is a cylinder and the normal is the
// component of (x_A - anchor) perpendicular to the cylinder's current axis, pointing from A to the
// axis, anchor being the interface sphere's centre carried by the cylinder: the sphere
// discretisation then adds no artificial interlock along the bar.
template <typename Law>
void evaluate_contacts(const Law& law, const ContactNetwork& net, const Bodies& bodies,
                       ContactState& cs, Real dt, const Vec3* anchor0 = nullptr) {
  const Vec3* x = bodies.position.data();
  const Vec3* x0 = bodies.position0.data();
  const Vec3* w = bodies.angular_velocity.data();
  const Quat* q = bodies.orientation.data();
  parallel_for(net.contact_count(), [&](Index c) {
    const Index a = net.particle_a[c];
    const Index b = net.particle_b[c];
    Vec3 n;
    if (anchor0) {
      const Vec3 axis = q[b] * (bodies.orientation0[b] * Vec3::UnitZ());
      const Vec3 anchor = x[b] + q[b] * (anchor0[c] - x0[b]);
      const Vec3 d = anchor - x[a];
      n = (d - d.dot(axis) * axis).normalized();
    } else {
      n = (x[b] - x[a]).normalized();
    }
    // SPEC 4: the plane's frame turns with the contact, carrying every point's shear history.
    const PlaneRotation rot{cs.normal[c], n, 0.5 * dt * (w[a] + w[b]).dot(n)};
    cs.normal[c] = n;
    Vec3 t1 = rot.turn_frame_axis(cs.tangent[c]);
    if (!(t1.squaredNorm() > 0.5)) t1 = any_perpendicular(n);  // only after a turn near 90 deg
    cs.tangent[c] = t1;
    const Vec3 t2 = n.cross(t1);
    const Eigen::Matrix3d ra = q[a].toRotationMatrix();
    const Eigen::Matrix3d rb = q[b].toRotationMatrix();
    // contact_kinematics.hpp: u_J is affine in r = p_J0 - x_A0, u_J = u0 + (R_B - R_A) r, and the
    // point sits at x_A + R_A r + u_J / 2. Built from small differences only, so it keeps full
    // precision far from the origin.
    const Vec3 dx = x[b] - x[a];
    const Vec3 u0 = dx - rb * (x0[b] - x0[a]);
    const Eigen::Matrix3d dr = rb - ra;
    Vec3 f = Vec3::Zero(), moment_a = Vec3::Zero();
    Real damage = 0.0, friction = 0.0;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
      const Vec3 r = net.point_position0[m] - x0[a];
      const Vec3 u = u0 + dr * r;
      LocalPointState& s = cs.point[m];
      const LocalPointConstants& pc = net.constants[m];
      const Vec3 us(u.dot(t1), u.dot(t2), 0.0);  // total shear displacement, in the frame
      const LawResult res = law.update(pc, s, u.dot(n) - s.un, us - s.us);  // (1)-(2), SPEC 4-5
      // On B; tension (fn > 0) pulls B back towards A.
      const Vec3 fp = -s.fn * n + s.fs.x() * t1 + s.fs.y() * t2;
      f += fp;
      moment_a += (ra * r + 0.5 * u).cross(fp);
      damage += res.dissipated - res.dissipated_friction;
      friction += res.dissipated_friction;
    }
    cs.force_b[c] = f;
    cs.torque_b[c] = moment_a - dx.cross(f);
    cs.torque_a[c] = -moment_a;
    cs.dissipated_damage[c] = damage;
    cs.dissipated_friction[c] = friction;
  });
}

}  // namespace rcdem
