#include "rcdem/solver/step_part.hpp"

#include "rcdem/core/parallel.hpp"

namespace rcdem {

BodyKinematics::BodyKinematics(const Bodies& bodies)
    : position(bodies.position),
      position_prev(bodies.position),
      rotation(static_cast<std::size_t>(bodies.size()), Eigen::Matrix3d::Identity()),
      rotation_prev(rotation) {
  pose.resize(bodies.size());
}

void BodyKinematics::update(const Bodies& bodies) {
  std::swap(rotation, rotation_prev);
  std::swap(position, position_prev);
  const auto form = [&](Index i) {
    rotation[i] = bodies.orientation[i].toRotationMatrix();
    position[i] = bodies.position[i];
    pose.set(i, bodies.position[i], bodies.orientation[i]);
  };
  if (only.empty()) {
    parallel_for(bodies.size(), form);
    return;
  }
  // The other bodies' poses are never read here: each rank's are their owners' business, and a
  // body in the list is formed every step, so its previous pose is the last step's.
  parallel_for(static_cast<Index>(only.size()),
               [&](Index k) { form(only[static_cast<std::size_t>(k)]); });
}

}  // namespace rcdem
