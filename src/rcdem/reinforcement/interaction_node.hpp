#pragma once
// The interaction node between two consecutive rigid cylinders A and B of a bar (paper 2.5,
// Figure 4; SPEC 7): where the bar's elasticity and strength are lumped.
//
// Geometry, recomputed every step from the two cylinders' current centres and orientations:
//   position (7) x_c = 0.5 (end of A + start of B),  axis (8) a_c = 0.5 (a_A + a_B), normalised.
// Springs (9) with SPEC 7's corrections, L = (L_A + L_B) / 2:
//   k_a = EA/L,  k_t = kappa G A / L (kappa = 0.9),  k_b = EI/L,  k_theta = G J / L.
// Law, as the parallel bond the paper follows: axial force N (scalar along a_c, tension
// positive), shear force V (vector normal to a_c), bending moment M_b (vector normal to a_c) and
// twisting moment M_t (scalar), all incremental and held in the node's frame, so that they turn
// with the node. Axial: elastic, then a perfectly plastic plateau at +-f_y A with elastic
// unloading; shear, bending and torsion elastic.
//
// Choice - total-displacement kinematics (as contacts, docs/model.md 4): the increments are
// differences of the node's total relative displacement and rotation, measured between the
// material points of A and B that met at the node at t = 0 and in a node frame carried half-way
// between A and B. Rigid motions of the pair, however large, give exactly no increment (summing
// velocity x dt would drift), and nothing needs the bodies' velocities.
#include <concepts>
#include <type_traits>

#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/reinforcement/rigid_cylinder.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

struct SteelMaterial {
  Real young_modulus = 200e9;   // E [Pa] (paper 3)
  Real poisson_ratio = 0.3;     // nu, G = E / (2 (1 + nu)) (SPEC 7)
  Real yield_strength = 500e6;  // f_y [Pa], per bar (Table 3)
  Real density = 7850.0;        // rho [kg/m^3] (SPEC 7)
};

// The four springs of (9) and the axial plateau.
struct NodeStiffness {
  Real axial;        // k_a [N/m]
  Real shear;        // k_t [N/m]
  Real bending;      // k_b [N m/rad]
  Real torsion;      // k_theta [N m/rad]
  Real yield_force;  // f_y A [N]
};

// (9) with SPEC 7's corrections, for cylinders of lengths L_A, L_B and bar diameter D.
NodeStiffness node_stiffness(Real length_a, Real length_b, Real diameter,
                             const SteelMaterial& steel);

// Constants of one node. Vectors and frames are in each cylinder's reference frame: the frame
// that the orientation passed to evaluate_node() maps to the world (so the solver may store
// either body-to-world orientations or rotations since t = 0, as long as it builds the node with
// the same convention).
struct InteractionNode {
  Vec3 arm_a, arm_b;      // centre -> end of A / start of B
  Vec3 axis_a, axis_b;    // the cylinders' axes
  Quat frame_a, frame_b;  // the node frame at t = 0 (z = a_c)
  Vec3 gap0;              // (start of B - end of A) at t = 0, node frame; 0 for a straight bar
  NodeStiffness k;
};

// Builds a node from the cylinders at t = 0 and the orientations the solver holds for them then.
InteractionNode make_interaction_node(const CylinderGeometry& a, const Quat& orientation_a,
                                      const CylinderGeometry& b, const Quat& orientation_b,
                                      Real diameter, const SteelMaterial& steel);

// History of one node, in the node frame (z = a_c). Starts zeroed.
struct NodeState {
  Real axial_force = 0.0;              // N, tension positive
  Vec3 shear_force = Vec3::Zero();     // V, (x, y, 0)
  Vec3 bending_moment = Vec3::Zero();  // M_b, (x, y, 0)
  Real twisting_moment = 0.0;          // M_t
  Real plastic_elongation = 0.0;       // accumulated signed plastic axial displacement [m]
  bool yielded = false;                // has reached the plateau at least once
  Vec3 displacement = Vec3::Zero();    // total relative displacement at the last update
  Vec3 rotation = Vec3::Zero();        // total relative rotation vector at the last update
};

struct NodeGeometry {
  Vec3 position;  // (7)
  Vec3 axis;      // (8)
};

// What the node does to its two cylinders in one update: forces and moments about each centre
// (equal and opposite forces; moments balance about any point), in the world frame.
struct NodeForces {
  Vec3 force_a = Vec3::Zero(), torque_a = Vec3::Zero();
  Vec3 force_b = Vec3::Zero(), torque_b = Vec3::Zero();
  Vec3 position = Vec3::Zero();  // (7)
  Vec3 axis = Vec3::Zero();      // (8)
  Real dissipated = 0;           // plastic work in this update [J], f_y A |plastic increment|
};

// A node's columns in the checkpoint (core/archive.hpp), in this order.
template <class Record, class S>
requires std::same_as<std::remove_const_t<S>, NodeState>
void archive_fields(Record& r, S& n) {
  r.put(named("axial_force", "N", n.axial_force));
  r.put(named("shear_force", "N", n.shear_force));
  r.put(named("bending_moment", "N*m", n.bending_moment));
  r.put(named("twisting_moment", "N*m", n.twisting_moment));
  r.put(named("plastic_elongation", "m", n.plastic_elongation));
  r.put(named("yielded", "-", n.yielded));
  r.put(named("displacement", "m", n.displacement));
  r.put(named("rotation", "rad", n.rotation));
}
template <class Record, class F>
requires std::same_as<std::remove_const_t<F>, NodeForces>
void archive_fields(Record& r, F& f) {
  r.put(named("force_a", "N", f.force_a));
  r.put(named("torque_a", "N*m", f.torque_a));
  r.put(named("force_b", "N", f.force_b));
  r.put(named("torque_b", "N*m", f.torque_b));
  r.put(named("position", "m", f.position));
  r.put(named("axis", "1", f.axis));
  r.put(named("dissipated", "J", f.dissipated));
}

// A node joining the material points of A and B at point_a and point_b (world, t = 0, distinct):
// a tie between two bars that touch (reinforcement/bar_ties.hpp). Its axis is the line from
// point_a to point_b, carried by both cylinders as (8) carries a bar node's; its springs (9) are
// those of a bar of `diameter` between cylinders of A's and B's lengths.
InteractionNode make_interaction_node_at(const CylinderGeometry& a, const Quat& orientation_a,
                                         const Vec3& point_a, const CylinderGeometry& b,
                                         const Quat& orientation_b, const Vec3& point_b,
                                         Real diameter, const SteelMaterial& steel);

// (7)-(8) for cylinders at x_a, q_a and x_b, q_b.
NodeGeometry node_geometry(const InteractionNode& node, const Vec3& x_a, const Quat& q_a,
                           const Vec3& x_b, const Quat& q_b);

// One update of one node from the cylinders' current centres and orientations: writes only
// `state`, so nodes may be updated in parallel and their forces gathered per body.
NodeForces evaluate_node(const InteractionNode& node, NodeState& state, const Vec3& x_a,
                         const Quat& q_a, const Vec3& x_b, const Quat& q_b);

// Elastic energy held in the node: N^2/2k_a + |V|^2/2k_t + |M_b|^2/2k_b + M_t^2/2k_theta.
Real node_elastic_energy(const InteractionNode& node, const NodeState& state);

}  // namespace rcdem
