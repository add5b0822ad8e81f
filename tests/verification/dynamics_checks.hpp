#pragma once
// For verification tests of the time step: the assembly's highest frequency from the solver's own
// force routines (dense, small specimens only), and whether a simulation runs stably.
#include <Eigen/Dense>
#include <cmath>

#include "rcdem/core/error.hpp"
#include "rcdem/core/rng.hpp"
#include "rcdem/solver/simulation.hpp"
#include "static_model.hpp"

namespace rcdem::test {

// omega_max of M^-1 K, K the tangent stiffness assembled from the solver's own force routines.
inline Real highest_frequency(const Simulation& sim) {
  const Bodies& b = sim.bodies();
  const test::StaticModel model{&sim.specimen().contacts, b, sim.plates(), sim.plate_contacts(), 1};
  const Eigen::MatrixXd K = model.tangent_stiffness();
  Eigen::VectorXd w(K.rows());  // M^-1/2 (spheres: isotropic inertia)
  for (Index i = 0; i < b.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      w[6 * i + a] = 1.0 / std::sqrt(b.mass[i]);
      w[6 * i + 3 + a] = 1.0 / std::sqrt(b.inertia[i][a]);
    }
  const Eigen::MatrixXd A = w.asDiagonal() * (0.5 * (K + K.transpose())) * w.asDiagonal();
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues().maxCoeff());
}

// Steps with random small velocities; true if it ran `steps` steps without an instability.
inline bool runs_stably(Simulation& sim, Real dt, int steps) {
  sim.set_time_step(dt);
  Rng rng(7);
  Bodies& b = sim.bodies();
  for (Index i = 0; i < b.size(); ++i) {
    b.velocity[i] = 1e-4 * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    b.angular_velocity[i] = Vec3::Zero();
  }
  try {
    for (int s = 0; s < steps; ++s) sim.step();
  } catch (const Error&) {
    return false;
  }
  return true;
}

}  // namespace rcdem::test
