#include "rcdem/reinforcement/interaction_node.hpp"

#include <algorithm>
#include <cmath>

#include "rcdem/core/error.hpp"
#include "rcdem/reinforcement/rigid_rotation.hpp"

namespace rcdem {

namespace {

// log of a rotation: the rotation vector (angle in [0, pi]).
Vec3 rotation_log(Quat d) {
  if (d.w() < 0.0) d.coeffs() = -d.coeffs();
  const Vec3 v = d.vec();
  const Real s = v.norm();
  if (!(s > 0.0)) return Vec3::Zero();
  return (2.0 * std::atan2(s, d.w()) / s) * v;  // no cancellation at small angles
}

// The node's current frame, and the relative rotation of B's copy of it against A's.
struct NodeFrame {
  Quat frame;     // node frame -> world; z = a_c (8)
  Vec3 rotation;  // total relative rotation of B against A, node-frame components
  NodeGeometry geometry;
  Vec3 gap;  // start of B minus end of A (world)
};

NodeFrame node_frame(const InteractionNode& node, const Vec3& x_a, const Quat& q_a, const Vec3& x_b,
                     const Quat& q_b) {
  // Each cylinder carries a copy of the t = 0 node frame; their relative rotation is the node's
  // total deformation rotation d. The frame half-way along d is then turned onto (8), from which
  // it differs only at second order (when bending and twist combine).
  const Quat carried_a = q_a * node.frame_a;
  const Quat carried_b = q_b * node.frame_b;
  const Vec3 theta = rotation_log(carried_a.conjugate() * carried_b);
  const Quat halfway = carried_a * rotation_exp(0.5 * theta);
  const Vec3 axis = (q_a * node.axis_a + q_b * node.axis_b).normalized();
  NodeFrame f;
  f.frame = Quat::FromTwoVectors(halfway * Vec3::UnitZ(), axis) * halfway;
  f.frame.normalize();
  f.rotation = f.frame.conjugate() * (carried_a * theta);
  const Vec3 end_a = x_a + q_a * node.arm_a;
  const Vec3 start_b = x_b + q_b * node.arm_b;
  f.geometry = {0.5 * (end_a + start_b), axis};  // (7), (8)
  f.gap = start_b - end_a;
  return f;
}

}  // namespace

NodeStiffness node_stiffness(Real length_a, Real length_b, Real diameter,
                             const SteelMaterial& steel) {
  if (!(length_a > 0.0) || !(length_b > 0.0) || !(diameter > 0.0))
    fail("bar node: cylinder lengths ({} m, {} m) and diameter ({} m) must be positive", length_a,
         length_b, diameter);
  const Real l = 0.5 * (length_a + length_b);
  const Real area = kPi * diameter * diameter / 4.0;
  const Real second_moment = kPi * std::pow(diameter, 4) / 64.0;
  const Real polar_moment = kPi * std::pow(diameter, 4) / 32.0;
  const Real e = steel.young_modulus;
  const Real g = e / (2.0 * (1.0 + steel.poisson_ratio));
  constexpr Real kShearCoefficient = 0.9;  // kappa (SPEC 7)
  // SPEC 7: the paper's (9) prints GI/L for the shear spring (not a force stiffness) and EJ/L
  // for the torsional one; a lumped beam segment of length L has kappa G A/L and G J/L.
  return {e * area / l, kShearCoefficient * g * area / l, e * second_moment / l,
          g * polar_moment / l, steel.yield_strength * area};
}

namespace {

// A node joining material points centre + arm of cylinders A and B (world vectors at t = 0), its
// axis at t = 0 along axis_a + axis_b, which the cylinders carry as they turn.
InteractionNode node_between(const CylinderGeometry& a, const Quat& orientation_a,
                             const Vec3& arm_a, const Vec3& axis_a, const CylinderGeometry& b,
                             const Quat& orientation_b, const Vec3& arm_b, const Vec3& axis_b,
                             Real diameter, const SteelMaterial& steel) {
  const Vec3 sum = axis_a + axis_b;
  if (!(sum.norm() > 1e-6)) fail("bar node: consecutive cylinders point in opposite directions");
  const Quat frame0 = orientation_for_axis(sum);  // z = (8) at t = 0
  const Quat to_a = orientation_a.conjugate();
  const Quat to_b = orientation_b.conjugate();
  InteractionNode node;
  node.arm_a = to_a * arm_a;
  node.arm_b = to_b * arm_b;
  node.axis_a = to_a * axis_a;
  node.axis_b = to_b * axis_b;
  node.frame_a = to_a * frame0;
  node.frame_b = to_b * frame0;
  node.gap0 = frame0.conjugate() * ((b.centre + arm_b) - (a.centre + arm_a));
  node.k = node_stiffness(a.length, b.length, diameter, steel);
  return node;
}

}  // namespace

InteractionNode make_interaction_node(const CylinderGeometry& a, const Quat& orientation_a,
                                      const CylinderGeometry& b, const Quat& orientation_b,
                                      Real diameter, const SteelMaterial& steel) {
  const Vec3 axis_a = a.axis.normalized();
  const Vec3 axis_b = b.axis.normalized();
  return node_between(a, orientation_a, 0.5 * a.length * axis_a, axis_a, b, orientation_b,
                      -0.5 * b.length * axis_b, axis_b, diameter, steel);
}

InteractionNode make_interaction_node_at(const CylinderGeometry& a, const Quat& orientation_a,
                                         const Vec3& point_a, const CylinderGeometry& b,
                                         const Quat& orientation_b, const Vec3& point_b,
                                         Real diameter, const SteelMaterial& steel) {
  const Vec3 across = point_b - point_a;
  if (!(across.norm() > 0.0)) fail("bar tie: the two bars' axes meet (expected touching bars)");
  const Vec3 n = across.normalized();
  return node_between(a, orientation_a, point_a - a.centre, n, b, orientation_b,
                      point_b - b.centre, n, diameter, steel);
}

NodeGeometry node_geometry(const InteractionNode& node, const Vec3& x_a, const Quat& q_a,
                           const Vec3& x_b, const Quat& q_b) {
  return node_frame(node, x_a, q_a, x_b, q_b).geometry;
}

NodeForces evaluate_node(const InteractionNode& node, NodeState& s, const Vec3& x_a,
                         const Quat& q_a, const Vec3& x_b, const Quat& q_b) {
  const NodeFrame f = node_frame(node, x_a, q_a, x_b, q_b);
  const NodeStiffness& k = node.k;
  // Total relative displacement and rotation of B against A in the node frame; their changes
  // since the last update are this step's increments.
  const Vec3 u = f.frame.conjugate() * f.gap - node.gap0;
  const Vec3 du = u - s.displacement;
  const Vec3 dtheta = f.rotation - s.rotation;
  s.displacement = u;
  s.rotation = f.rotation;

  // Axial (SPEC 7): elastic trial, then the plateau +-f_y A; what exceeds it is plastic flow.
  Real dissipated = 0.0;
  const Real trial = s.axial_force + k.axial * du.z();
  s.axial_force = std::clamp(trial, -k.yield_force, k.yield_force);
  if (s.axial_force != trial) {
    const Real plastic = (trial - s.axial_force) / k.axial;
    s.plastic_elongation += plastic;
    s.yielded = true;
    dissipated = k.yield_force * std::abs(plastic);  // work at constant force on the plateau
  }
  s.shear_force += k.shear * Vec3(du.x(), du.y(), 0.0);
  s.bending_moment += k.bending * Vec3(dtheta.x(), dtheta.y(), 0.0);
  s.twisting_moment += k.torsion * dtheta.z();

  // The node resists B's displacement and rotation against A (tension pulls B back to A, SPEC 1);
  // A gets the opposite. The force acts at the node (7), hence the moments of F about each centre.
  const Vec3 force = f.frame * (s.shear_force + s.axial_force * Vec3::UnitZ());
  const Vec3 moment = f.frame * (s.bending_moment + s.twisting_moment * Vec3::UnitZ());
  const Vec3& x_c = f.geometry.position;
  NodeForces out;
  out.force_b = -force;
  out.torque_b = -moment + (x_c - x_b).cross(out.force_b);
  out.force_a = force;
  out.torque_a = moment + (x_c - x_a).cross(out.force_a);
  out.position = x_c;
  out.axis = f.geometry.axis;
  out.dissipated = dissipated;
  return out;
}

Real node_elastic_energy(const InteractionNode& node, const NodeState& s) {
  const NodeStiffness& k = node.k;
  return 0.5 * (s.axial_force * s.axial_force / k.axial + s.shear_force.squaredNorm() / k.shear +
                s.bending_moment.squaredNorm() / k.bending +
                s.twisting_moment * s.twisting_moment / k.torsion);
}

}  // namespace rcdem
