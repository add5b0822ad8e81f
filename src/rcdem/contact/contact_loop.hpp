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
    const PlaneRotation rot{cs.normal[c].cross(n), (0.5 * dt * (w[a] + w[b]).dot(n)) * n, n};
    cs.normal[c] = n;
    const Eigen::Matrix3d ra = q[a].toRotationMatrix();
    const Eigen::Matrix3d rb = q[b].toRotationMatrix();
    Vec3 f = Vec3::Zero(), tb = Vec3::Zero(), ta = Vec3::Zero();
    Real strain = 0.0, damage = 0.0, friction = 0.0;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
      const PointKinematics k =
          point_kinematics(net.point_position0[m], x[a], x0[a], ra, x[b], x0[b], rb, n);
      LocalPointState& s = cs.point[m];
      const LocalPointConstants& pc = net.constants[m];
      s.fs = rot.apply(s.fs);
      s.us = rot.apply(s.us);
      const LawResult r = law.update(pc, s, k.un - s.un, k.us - s.us);  // (1)-(2), SPEC 4-5
      const Vec3 fp = -s.fn * n + s.fs;  // on B; tension (fn > 0) pulls B back towards A
      f += fp;
      tb += (k.position - x[b]).cross(fp);
      ta -= (k.position - x[a]).cross(fp);
      strain += 0.5 * s.fn * s.fn / pc.kn + 0.5 * s.fs.squaredNorm() / pc.ks;
      damage += r.dissipated - r.dissipated_friction;
      friction += r.dissipated_friction;
    }
    cs.force_b[c] = f;
    cs.torque_b[c] = tb;
    cs.torque_a[c] = ta;
    cs.strain_energy[c] = strain;
    cs.dissipated_damage[c] = damage;
    cs.dissipated_friction[c] = friction;
  });
}

}  // namespace rcdem
