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
  parallel_for(bodies.size(), [&](Index i) {
    rotation[i] = bodies.orientation[i].toRotationMatrix();
    position[i] = bodies.position[i];
    pose.set(i, bodies.position[i], bodies.orientation[i]);
  });
}

}  // namespace rcdem
