#include "rcdem/state/bodies.hpp"

namespace rcdem {

Bodies bodies_from_particles(const Particles& p, Real density, Real mass_scaling) {
  Bodies b;
  const auto n = static_cast<std::size_t>(p.size());
  b.position = p.position;
  b.position0 = p.position;
  b.velocity.assign(n, Vec3::Zero());
  b.angular_velocity.assign(n, Vec3::Zero());
  b.orientation.assign(n, Quat::Identity());
  b.orientation0.assign(n, Quat::Identity());
  b.mass.resize(n);
  b.inertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    b.mass[i] = mass_scaling * density * p.cell_volume[i];
    b.inertia[i] = Vec3::Constant(0.4 * b.mass[i] * p.radius[i] * p.radius[i]);
  }
  b.force.assign(n, Vec3::Zero());
  b.torque.assign(n, Vec3::Zero());
  b.radius = p.radius;
  return b;
}

}  // namespace rcdem
