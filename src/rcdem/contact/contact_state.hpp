#pragma once
// What the contact loop keeps between steps (the history of every local point, the contact
// normals) and what it hands to the gather (one force and two torques per contact, and the
// contact's energy terms), all as flat arrays.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "rcdem/contact/local_point_records.hpp"
#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// A unit vector perpendicular to the unit vector n.
Vec3 any_perpendicular(const Vec3& n);

// How many points of a contact, or of a block of contacts, became damaged (D left 0) and broken
// (D reached 1) in one step.
struct PointTransitions {
  Index damaged = 0, broken = 0;
};

struct ContactState {
  LocalPointRecords point;   // per local point, frame components
  std::vector<Vec3> normal;  // per contact: unit A -> B at the last evaluation
  // Per contact: the first axis t1 of the contact plane's frame (t2 = n x t1). The frame turns
  // with the contact (SPEC 4), and every point's shear vectors fs, us are kept as components
  // (along t1, along t2, 0) in it: one frame rotated per contact instead of two vectors per point.
  std::vector<Vec3> tangent;

  // Per contact, written by each evaluation (the two dissipations only by the point loop: a
  // contact evaluated from its sums dissipates nothing, and the ledger then reads the blocks'
  // sums below, not these).
  std::vector<Vec3> force_b;              // total force on B (on A: its opposite)
  std::vector<Vec3> torque_b;             // about B's centre
  std::vector<Vec3> torque_a;             // about A's centre
  std::vector<Real> dissipated_damage;    // during this step [J]
  std::vector<Real> dissipated_friction;  // during this step [J]
  // The same two summed per block of the blocked loop (evaluate_contacts with condensation), in
  // contact order, while the block is in cache: the step's ledger then adds a few hundred numbers
  // in a fixed order instead of passing over every contact on one thread (a twentieth of an
  // elastic step at 2 threads).
  std::vector<Real> block_damage, block_friction;

  // How many points are damaged (D > 0, broken ones included) and broken (D = 1), kept by the
  // loop from each point's transitions (contact_loop.hpp, PointTransitions) rather than counted
  // over every point when a history row asks; and the contacts in which points broke, one entry
  // per contact and step, in contact order within a step (run/crack_record.cpp reads the tail it
  // has not seen). Recounted from the points at init and on restore, when the log starts empty.
  Index damaged_or_broken = 0, broken = 0;
  std::vector<Index> broken_contact_log;
  std::vector<PointTransitions> block_transitions;  // per block of the loop
  std::vector<std::uint8_t> newly_broken_contact;   // per contact, cleared by the tally
  // A distributed run's share (solver/decomposition.hpp): the loop's blocks this rank evaluates
  // (all unless `listed`), and those whose transitions it counts and logs, [counted_begin,
  // counted_end) (the others' flags are only cleared).
  bool listed = false;
  std::vector<Index> evaluated_blocks;
  Index counted_begin = 0, counted_end = std::numeric_limits<Index>::max();
  const std::vector<Index>* evaluated() const { return listed ? &evaluated_blocks : nullptr; }
  void size_blocks(Index contacts, Index block);
  void tally_transitions(Index block);  // the blocks' transitions into the totals and the log
  void recount();

  // Normals at t = 0: centre to centre, or (with anchors) perpendicular to the bar's axis.
  // A point's shear force and accumulated shear displacement in the world frame.
  Vec3 shear_force(Index c, Index m) const { return to_world(c, point[m].fs); }
  Vec3 shear_displacement(Index c, Index m) const { return to_world(c, point[m].us); }
  Vec3 to_world(Index c, const Vec3& local) const {
    return local.x() * tangent[c] + local.y() * normal[c].cross(tangent[c]);
  }

  // The elastic energy held by contact c's local points now, each as its law stores it (SPEC 11).
  // Not kept per step: the ledger asks for it when it reports.
  template <typename Law>
  Real strain_energy(const Law& law, const ContactNetwork& net, Index c) const {
    Real e = 0.0;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m)
      e += law.elastic_energy(net.constants[m], point[m]);
    return e;
  }

  // The checkpoint's sections `name` (per contact) and `name`.points (core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, const std::string& name, Self& c) {
    ar.table(name, c.normal.size(), column("normal", "1", c.normal),
             column("tangent", "1", c.tangent), column("force_b", "N", c.force_b),
             column("torque_b", "N*m", c.torque_b), column("torque_a", "N*m", c.torque_a),
             column("dissipated_damage", "J", c.dissipated_damage),
             column("dissipated_friction", "J", c.dissipated_friction));
    ar.table(name + ".points", c.point.records.size(), column("record", "", c.point.records));
    if constexpr (Archive::loading)
      if (ar.applying()) c.recount();
  }

  void init(const ContactNetwork& net, const std::vector<Vec3>& positions,
            const std::vector<Vec3>* anchor0 = nullptr, const std::vector<Vec3>* axis0 = nullptr);
};

}  // namespace rcdem
