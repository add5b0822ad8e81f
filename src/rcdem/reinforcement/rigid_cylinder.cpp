#include "rcdem/reinforcement/rigid_cylinder.hpp"

#include <cmath>

#include "rcdem/core/error.hpp"

namespace rcdem {

CylinderInertia solid_cylinder_inertia(Real diameter, Real length, Real density) {
  if (!(diameter > 0.0) || !(length > 0.0) || !(density > 0.0))
    fail("cylinder: diameter ({} m), length ({} m) and density ({} kg/m^3) must be positive",
         diameter, length, density);
  const Real r = 0.5 * diameter;
  const Real m = density * kPi * r * r * length;
  const Real it = m * (3.0 * r * r + length * length) / 12.0;
  return {m, Vec3(it, it, 0.5 * m * r * r)};  // I_a = m r^2 / 2 = m D^2 / 8
}

Quat orientation_for_axis(const Vec3& axis) {
  const Real len = axis.norm();
  if (!(len > 0.0) || !std::isfinite(len)) fail("cylinder: the axis must be a non-zero vector");
  const Vec3 a = axis / len;
  // Half-way quaternion (1 + z.a, z x a), well conditioned while a.z >= 0. Otherwise first a half
  // turn about x (z -> -z), then the same construction from -z, so that axes close to -z are
  // as accurate as the rest (Eigen's FromTwoVectors snaps them to an exact half turn).
  Quat q = a.z() >= 0.0 ? Quat(1.0 + a.z(), -a.y(), a.x(), 0.0)
                        : Quat(1.0 - a.z(), a.y(), -a.x(), 0.0) * Quat(0.0, 1.0, 0.0, 0.0);
  q.normalize();
  return q;
}

}  // namespace rcdem
