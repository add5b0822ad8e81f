#pragma once
// Kinematics of a local point (SPEC 4), and the rotation of its shear history with the contact.
//
// The relative displacement at local point J is computed in total form from the two particles'
// material points that coincided with J at t = 0:
//   u_J = (x_B + R_B (p_J0 - x_B0)) - (x_A + R_A (p_J0 - x_A0)).
// For any rigid motion of the pair (R_A = R_B = R, x_B - x_A = R (x_B0 - x_A0)) this is zero to
// rounding, however large the rotation, and it turns with the pair. Summing v.n dt instead, as
// the incremental form (1)-(2) reads literally, drifts by |d| theta^2 / 2 per step under a
// rotation of theta per step (1e-5 m over a quarter turn in 1000 steps: fifteen times the elastic
// limit of a Table 2 contact). The law still receives increments: du = u_J(now) - u_J(before).
#include <cmath>

#include "rcdem/core/small_angle.hpp"
#include "rcdem/core/types.hpp"

namespace rcdem {

struct PointKinematics {
  Vec3 position;  // current position of J: the mean of the two material points
  Real un;        // total normal displacement, opening positive
  Vec3 us;        // total shear displacement, in the plane normal to n
};

[[gnu::always_inline]] inline PointKinematics point_kinematics(
    const Vec3& p0, const Vec3& xa, const Vec3& xa0, const Eigen::Matrix3d& ra, const Vec3& xb,
    const Vec3& xb0, const Eigen::Matrix3d& rb, const Vec3& n) {
  const Vec3 pa = xa + ra * (p0 - xa0);
  const Vec3 pb = xb + rb * (p0 - xb0);
  const Vec3 u = pb - pa;
  PointKinematics k;
  k.position = 0.5 * (pa + pb);
  k.un = u.dot(n);
  k.us = u - k.un * n;
  return k;
}

// A contact's offset displacement u0 = dx - R_B r0 (dx = x_B - x_A, r0 = x_B0 - x_A0), component i
// from row i of R_B: a small difference of large terms, so its rounding sets how closely two
// evaluations of a contact agree, and the point loop and the condensed contacts' SIMD kernel
// (elastic_condensation.cpp) both take it from here. Scalars only: a local array whose address is
// taken in a SIMD loop becomes a per-lane array in memory.
[[gnu::always_inline]] inline Real offset_displacement(Real dx_i, Real rb_i0, Real rb_i1,
                                                       Real rb_i2, Real r0x, Real r0y, Real r0z) {
  return dx_i - (rb_i0 * r0x + rb_i1 * r0y + rb_i2 * r0z);
}

// cos and sin of a pair's spin in one step (core/small_angle.hpp below 0.1 rad, libm above). A
// libm sincos per contact is a call in the hot loop.
[[gnu::always_inline]] inline void small_angle_cos_sin(Real a, Real& c, Real& s) {
  if (is_small_angle(a * a)) {
    Real sinc;
    small_angle_cos_sinc(a * a, c, sinc);
    s = a * sinc;
  } else {
    c = std::cos(a);
    s = std::sin(a);
  }
}

// SPEC 4: the contact plane's frame is carried from the previous step into the current one:
// turned by the rotation taking the old normal to the new one (about n_old x n_new), then by the
// pair's mean spin about the new normal, then cleared of any normal component and renormalised.
// Both turns are exact rotations (Rodrigues), not their first-order forms: done once per contact
// rather than once per point and vector, they cost little, and a frame carried through a 90
// degree rigid rotation then loses no accuracy at all with the step (a shear history on the
// softening envelope, where any error in the carried displacement turns into slip, stays put).
struct PlaneRotation {
  Vec3 n_old;  // the normal of the previous step
  Vec3 n;      // the new normal
  Real spin;   // 0.5 (w_A + w_B).n dt: the pair's turn about n during the step [rad]

  [[gnu::always_inline]] Vec3 turn_frame_axis(const Vec3& t) const {
    // R v = c v + k x v + k (k.v) / (1 + c), k = n_old x n, c = n_old . n (unit vectors).
    const Vec3 k = n_old.cross(n);
    const Real c = n_old.dot(n);
    Vec3 r = c > -0.5 ? Vec3(c * t + k.cross(t) + (k.dot(t) / (1.0 + c)) * k) : t;
    // About n: t stays perpendicular to n, so R t = cos(spin) t + sin(spin) n x t.
    Real cos_spin, sin_spin;
    small_angle_cos_sin(spin, cos_spin, sin_spin);
    r = cos_spin * r + sin_spin * n.cross(r);
    r -= r.dot(n) * n;
    const Real r2 = r.squaredNorm();
    return r2 > 0.0 ? Vec3(r / std::sqrt(r2)) : Vec3::Zero();
  }
};
}  // namespace rcdem
