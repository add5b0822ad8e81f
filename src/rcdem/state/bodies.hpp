#pragma once
// Rigid bodies with 6 degrees of freedom (SPEC 6), structure of arrays. Spheres now; the bars'
// cylinders (SPEC 7) join the same arrays with their own, non-isotropic inertia.
#include <Eigen/Geometry>
#include <vector>

#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/state/particles.hpp"

namespace rcdem {

using Quat = Eigen::Quaternion<Real>;

struct Bodies {
  std::vector<Vec3> position, position0;  // centre of mass now and at t = 0
  std::vector<Vec3> velocity;             // at the half step (leap-frog)
  std::vector<Vec3> angular_velocity;     // world frame, at the half step
  std::vector<Quat> orientation;          // rotation since t = 0 (identity at t = 0)
  std::vector<Quat> orientation0;         // body frame -> world at t = 0 (cylinders: z = axis)
  std::vector<Real> mass;
  std::vector<Vec3> inertia;           // principal moments in the body frame
  std::vector<Vec3> angular_momentum;  // world frame, at the half step
  std::vector<Vec3> force, torque;     // gathered each step
  std::vector<Real> radius;            // size scale, for the instability check

  Index size() const { return static_cast<Index>(position.size()); }

  // The checkpoint's "bodies" table (core/archive.hpp): what a step changes. Reference positions,
  // orientations, masses and inertias come with the regenerated specimen.
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& b) {
    ar.table("bodies", b.position.size(), column("position", "m", b.position),
             column("velocity", "m/s", b.velocity),
             column("angular_velocity", "rad/s", b.angular_velocity),
             column("orientation", "1", b.orientation),
             column("angular_momentum", "kg*m^2/s", b.angular_momentum),
             column("force", "N", b.force), column("torque", "N*m", b.torque));
  }
};

// The first `count` particles as bodies. Mass = density x Voronoi cell volume, so the specimen
// weighs density x volume; inertia 2/5 m r^2 with r the sphere radius (SPEC 6, assumed).
// `mass_scaling` multiplies both.
Bodies bodies_from_particles(const Particles& particles, Real density, Real mass_scaling,
                             Index count = -1);

// Appends a body (a bar's cylinder) with its mass, principal inertia and principal frame at t = 0.
void add_body(Bodies& b, const Vec3& x, Real mass, const Vec3& inertia, const Quat& axes0,
              Real size);

}  // namespace rcdem
