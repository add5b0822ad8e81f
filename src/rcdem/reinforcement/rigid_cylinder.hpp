#pragma once
// One rigid cylinder of a steel bar (paper 2.5, SPEC 7): its exact mass and principal inertia, and
// the orientation that puts its body frame in the world. Body frame: the cylinder's axis is body z,
// so the inertia tensor is diagonal there with I_x = I_y (transverse) and I_z (about the axis).
#include "rcdem/core/types.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

// Where a cylinder lies: centre of mass, unit axis (from the bar's start towards its end), length.
struct CylinderGeometry {
  Vec3 centre;
  Vec3 axis;
  Real length;
};

struct CylinderInertia {
  Real mass;
  Vec3 principal_inertia;  // body frame: (I_t, I_t, I_a)
};

// Solid cylinder of diameter D, length L, density rho:
//   m = rho pi D^2 L / 4,  I_a = m D^2 / 8,  I_t = m (3 (D/2)^2 + L^2) / 12.
CylinderInertia solid_cylinder_inertia(Real diameter, Real length, Real density);

// A rotation taking body z onto `axis` (any length > 0), to rounding for every direction: the
// smallest one when axis.z >= 0. Where body x and y end up is immaterial (I_x = I_y).
Quat orientation_for_axis(const Vec3& axis);

}  // namespace rcdem
