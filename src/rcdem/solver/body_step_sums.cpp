#include "rcdem/solver/body_step_sums.hpp"

namespace rcdem {

BodyStepSums BodyStepSums::build(const Bodies& bodies, const std::vector<std::int64_t>& driven) {
  BodyStepSums s;
  const auto n = static_cast<std::size_t>(bodies.size());
  s.damping_work.assign(n, 0.0);
  s.kinetic.assign(n, 0.0);
  s.jumped.assign(n, 0);
  while (s.spheres < bodies.size() && driven[static_cast<std::size_t>(s.spheres)] < 0 &&
         bodies.inertia[s.spheres].x() == bodies.inertia[s.spheres].y() &&
         bodies.inertia[s.spheres].y() == bodies.inertia[s.spheres].z())
    ++s.spheres;
  s.blocks.assign(static_cast<std::size_t>((s.spheres + kSphereBlock - 1) / kSphereBlock), Block{});
  return s;
}

}  // namespace rcdem
