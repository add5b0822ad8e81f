#pragma once
// What the contact loop keeps between steps (the history of every local point, the contact
// normals) and what it hands to the gather (one force and two torques per contact, and the
// contact's energy terms), all as flat arrays.
#include <vector>

#include "rcdem/contact/laws/local_point_state.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

struct ContactState {
  std::vector<LocalPointState> point;  // per local point
  std::vector<Vec3> normal;            // per contact: unit A -> B at the last evaluation

  // Per contact, written by each evaluation.
  std::vector<Vec3> force_b;              // total force on B (on A: its opposite)
  std::vector<Vec3> torque_b;             // about B's centre
  std::vector<Vec3> torque_a;             // about A's centre
  std::vector<Real> strain_energy;        // stored in the contact's springs now [J]
  std::vector<Real> dissipated_damage;    // during this step [J]
  std::vector<Real> dissipated_friction;  // during this step [J]

  // Normals at t = 0: centre to centre, or (with anchors) perpendicular to the bar's axis.
  void init(const ContactNetwork& net, const std::vector<Vec3>& positions,
            const std::vector<Vec3>* anchor0 = nullptr, const std::vector<Vec3>* axis0 = nullptr);
};

}  // namespace rcdem
