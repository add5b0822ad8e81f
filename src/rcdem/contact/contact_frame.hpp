#pragma once
// A contact's frame and what its points read of the kinematics, formed once per contact
// (contact_loop.hpp: contact_frame; held_contacts.hpp).
#include "rcdem/core/types.hpp"

namespace rcdem {

// A contact's frame and the kinematics its points read: evaluate_contact's first half. The
// blocked loop forms them for all the contacts of a block that visit their points before it visits
// any point, so that the out-of-order core overlaps the contacts' chains of dependent operations
// (normal, frame turn, products) instead of waiting on each between two contacts' ~100
// instructions per point (measured in bench/RESULTS.md).
struct ContactFrame {
  Vec3 n, t1, t2;
  Vec3 xa0;              // A's centre at t = 0
  Vec3 dx;               // x_B - x_A
  Vec3 disp0;            // E^T u0
  Eigen::Matrix3d disp;  // E^T (R_B - R_A)
  Eigen::Matrix3d arm;   // E^T (R_A + R_B) / 2
  bool intact;           // every point intact: any frame will do
};

}  // namespace rcdem
