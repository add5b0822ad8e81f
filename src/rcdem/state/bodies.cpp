#include "rcdem/state/bodies.hpp"

namespace rcdem {

Bodies bodies_from_particles(const Particles& p, Real density, Real mass_scaling, Index count) {
  Bodies b;
  const auto n = static_cast<std::size_t>(count < 0 ? p.size() : count);
  b.position.assign(p.position.begin(), p.position.begin() + static_cast<std::ptrdiff_t>(n));
  b.position0 = b.position;
  b.velocity.assign(n, Vec3::Zero());
  b.angular_velocity.assign(n, Vec3::Zero());
  b.orientation.assign(n, Quat::Identity());
  b.orientation0.assign(n, Quat::Identity());
  b.angular_momentum.assign(n, Vec3::Zero());
  b.mass.resize(n);
  b.inertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    b.mass[i] = mass_scaling * density * p.cell_volume[i];
    b.inertia[i] = Vec3::Constant(0.4 * b.mass[i] * p.radius[i] * p.radius[i]);
  }
  b.force.assign(n, Vec3::Zero());
  b.torque.assign(n, Vec3::Zero());
  b.radius.assign(p.radius.begin(), p.radius.begin() + static_cast<std::ptrdiff_t>(n));
  return b;
}

void add_body(Bodies& b, const Vec3& x, Real mass, const Vec3& inertia, const Quat& axes0,
              Real size) {
  b.position.push_back(x);
  b.position0.push_back(x);
  b.velocity.push_back(Vec3::Zero());
  b.angular_velocity.push_back(Vec3::Zero());
  b.orientation.push_back(Quat::Identity());
  b.orientation0.push_back(axes0);
  b.mass.push_back(mass);
  b.inertia.push_back(inertia);
  b.angular_momentum.push_back(Vec3::Zero());
  b.force.push_back(Vec3::Zero());
  b.torque.push_back(Vec3::Zero());
  b.radius.push_back(size);
}

}  // namespace rcdem
