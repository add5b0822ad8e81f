#include "rcdem/contact/contact_state.hpp"

#include <algorithm>
#include <cmath>

namespace rcdem {

Vec3 any_perpendicular(const Vec3& n) {
  // Cross with the world axis least aligned with n: never degenerate.
  const int k = std::abs(n.x()) < std::abs(n.y()) ? (std::abs(n.x()) < std::abs(n.z()) ? 0 : 2)
                                                  : (std::abs(n.y()) < std::abs(n.z()) ? 1 : 2);
  return n.cross(Vec3::Unit(k)).normalized();
}

void ContactState::init(const ContactNetwork& net, const std::vector<Vec3>& x,
                        const std::vector<Vec3>* anchor0, const std::vector<Vec3>* axis0) {
  const auto nc = static_cast<std::size_t>(net.contact_count());
  point.init(net);
  normal.resize(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    if (anchor0) {
      const Vec3& axis = (*axis0)[c];
      const Vec3 d = (*anchor0)[c] - x[net.particle_a[c]];
      normal[c] = (d - d.dot(axis) * axis).normalized();
    } else {
      normal[c] = (x[net.particle_b[c]] - x[net.particle_a[c]]).normalized();
    }
  }
  tangent.resize(nc);
  for (std::size_t c = 0; c < nc; ++c) tangent[c] = any_perpendicular(normal[c]);
  force_b.assign(nc, Vec3::Zero());
  torque_b.assign(nc, Vec3::Zero());
  torque_a.assign(nc, Vec3::Zero());
  dissipated_damage.assign(nc, 0.0);
  dissipated_friction.assign(nc, 0.0);
  recount();
}

void ContactState::size_blocks(Index contacts, Index block) {
  const auto blocks = static_cast<std::size_t>((contacts + block - 1) / block);
  if (block_transitions.size() == blocks) return;  // the first step only
  block_transitions.assign(blocks, PointTransitions{});
  newly_broken_contact.assign(static_cast<std::size_t>(contacts), 0);
}

void ContactState::tally_transitions(Index block) {
  const auto contacts = static_cast<Index>(newly_broken_contact.size());
  for (std::size_t k = 0; k < block_transitions.size(); ++k) {
    const PointTransitions& t = block_transitions[k];
    const auto kb = static_cast<Index>(k);
    const bool counted = kb >= counted_begin && kb < counted_end;
    if (counted) {
      damaged_or_broken += t.damaged;
      broken += t.broken;
    }
    if (t.broken == 0) continue;
    const Index begin = kb * block;
    for (Index c = begin; c < std::min(begin + block, contacts); ++c) {
      std::uint8_t& flag = newly_broken_contact[static_cast<std::size_t>(c)];
      if (!flag) continue;
      if (counted) broken_contact_log.push_back(c);
      flag = 0;
    }
  }
}

void ContactState::recount() {
  damaged_or_broken = broken = 0;
  for (const LocalPointRecord& r : point.records) {
    damaged_or_broken += r.history.damage > 0.0;
    broken += r.history.damage >= 1.0;
  }
  broken_contact_log.clear();
}

}  // namespace rcdem
