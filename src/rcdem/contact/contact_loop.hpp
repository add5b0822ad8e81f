#pragma once
// The loop over contacts and their local points, written once for every law (the law is a
// template parameter, chosen once per step). Each contact writes only its own outputs, so the
// loop runs in parallel and the result does not depend on the thread count.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include <type_traits>

#include "rcdem/contact/contact_frame.hpp"
#include "rcdem/contact/contact_kinematics.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/damaged_condensation.hpp"
#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/contact/laws/bilinear_softening.hpp"
#include "rcdem/core/parallel.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// What one local point adds to its contact's sums, in the contact's frame.
struct PointSums {
  Real f_n = 0, f_1 = 0, f_2 = 0;  // force on B
  Real m_n = 0, m_1 = 0, m_2 = 0;  // its moment about A's centre
  Real damage = 0, friction = 0;   // dissipated this step
  Real point_damage = 0;           // the point's D after the step
  Real outside = 0;                // 1 if the point left its envelope (capped or damaged)
};

// One local point of a contact, in the contact's frame (see evaluate_contacts): advances its
// history by the law and returns what it adds to the contact's sums. GCC vectorises the loop over
// a contact's points for the EL law only; BL's branches keep it scalar, and that is the faster
// form: a branch-free elastic pass in SIMD lanes (4 or 8) with a scalar pass for the points that
// leave the elastic range was 7-9% slower (bench/RESULTS.md, session 5), as was a full 8-lane
// pass with idle lanes masked for EL (6%).
template <typename Law>
struct PointUpdate {
  const Law& law;
  const Vec3* p0;
  const LocalPointConstants* constants;
  LocalPointPointers history;
  Vec3 xa0;              // A's centre at t = 0
  Vec3 disp0;            // E^T u0
  Eigen::Matrix3d disp;  // E^T (R_B - R_A)
  Eigen::Matrix3d arm;   // E^T (R_A + R_B) / 2

  [[gnu::always_inline]] PointSums operator()(Index m) const {
    const Real rx = p0[m].x() - xa0.x(), ry = p0[m].y() - xa0.y(), rz = p0[m].z() - xa0.z();
    // Total displacement in the frame: opening along n, shear along t1, t2.
    const Real u_n = disp0.x() + disp(0, 0) * rx + disp(0, 1) * ry + disp(0, 2) * rz;
    const Real u_1 = disp0.y() + disp(1, 0) * rx + disp(1, 1) * ry + disp(1, 2) * rz;
    const Real u_2 = disp0.z() + disp(2, 0) * rx + disp(2, 1) * ry + disp(2, 2) * rz;
    PlanePointState s = history.load(m);
    const LawResult res = law.update(constants[m], s, u_n, PlaneVec{u_1, u_2});  // (1)-(2)
    history.store(m, s);
    PointSums out;
    out.point_damage = s.damage;
    // On B; tension (fn > 0) pulls B back towards A.
    out.f_n = -s.fn;
    out.f_1 = s.fs.x;
    out.f_2 = s.fs.y;
    out.damage = res.dissipated - res.dissipated_friction;
    out.friction = res.dissipated_friction;
    out.outside = res.left_envelope ? 1.0 : 0.0;
    // The lever arm: E^T u0 / 2 + arm r.
    const Real a_n = 0.5 * disp0.x() + arm(0, 0) * rx + arm(0, 1) * ry + arm(0, 2) * rz;
    const Real a_1 = 0.5 * disp0.y() + arm(1, 0) * rx + arm(1, 1) * ry + arm(1, 2) * rz;
    const Real a_2 = 0.5 * disp0.z() + arm(2, 0) * rx + arm(2, 1) * ry + arm(2, 2) * rz;
    out.m_n = a_1 * out.f_2 - a_2 * out.f_1;
    out.m_1 = a_2 * out.f_n - a_n * out.f_2;
    out.m_2 = a_n * out.f_1 - a_1 * out.f_n;
    return out;
  }
};

// Contact c's points advanced by the law in frame f (phi: the force on B, mom: its moment about
// A's centre, both in the frame).
template <typename Law>
[[gnu::always_inline]] inline PointTotals advance_points(const Law& law, const ContactInputs& in,
                                                         ContactState& cs, Index c,
                                                         const ContactFrame& f) {
  const ContactNetwork& net = in.net;
  Real phi_n = 0.0, phi_1 = 0.0, phi_2 = 0.0, mom_n = 0.0, mom_1 = 0.0, mom_2 = 0.0;
  Real damage = 0.0, friction = 0.0, max_damage = 0.0, outside = 0.0;
  const PointUpdate<Law> point{law,
                               net.point_position0.data(),
                               net.constants.data(),
                               cs.point.pointers(),
                               in.x0[net.particle_a[c]],
                               f.disp0,
                               f.disp,
                               f.arm};
  const Index begin = net.point_begin[c], end = net.point_begin[c + 1];
#pragma omp simd reduction(+ : phi_n, phi_1, phi_2, mom_n, mom_1, mom_2, damage, friction, \
                               outside) reduction(max : max_damage)
  for (Index m = begin; m < end; ++m) {
    const PointSums o = point(m);
    phi_n += o.f_n;
    phi_1 += o.f_1;
    phi_2 += o.f_2;
    mom_n += o.m_n;
    mom_1 += o.m_1;
    mom_2 += o.m_2;
    damage += o.damage;
    friction += o.friction;
    outside += o.outside;
    max_damage = std::max(max_damage, o.point_damage);
  }
  return {phi_n, phi_1, phi_2, mom_n, mom_1, mom_2, damage, friction, max_damage, outside};
}

// One contact through its points (kPointsOnly: only the points' histories and the frame, for
// ElasticCondensation's catch-up; nothing the gather reads).
//
// Everything per point is done in the contact's frame (ContactFrame), with matrices formed once
// per contact, so that a point costs two 3x3 products, the law and a cross product, all on plain
// scalars (in SIMD lanes for the EL law, see PointUpdate). The frame turns with the contact
// (SPEC 4), carrying the points' shear histories, except while every point of the contact is
// intact: their forces are then independent of the frame (kn u_n, -ks u_s), so it is any axis
// across n, as ElasticCondensation's catch-up draws it.
//
// A damaged contact (with `cond`) whose points all stayed inside their envelopes is handed to the
// damaged condensation (damaged_condensation.hpp), which evaluates it from sums from the next step
// on while they stay there.
template <typename Law, bool kPointsOnly = false>
[[gnu::always_inline]] inline void evaluate_contact(const Law& law, const ContactInputs& in,
                                                    ContactState& cs, ElasticCondensation* cond,
                                                    Index c) {
  const ContactNetwork& net = in.net;
  const Index a = net.particle_a[c];
  const Index b = net.particle_b[c];
  const Vec3 n = contact_normal(in, a, b, c);
  const bool intact = cond && cond->intact[c];
  const Vec3 t1 = intact ? any_perpendicular(n) : turned_frame_axis(in, cs, a, b, c, n);
  cs.normal[c] = n;
  cs.tangent[c] = t1;
  const ContactFrame f = contact_frame(in, a, b, n, t1);
  const PointTotals t = advance_points(law, in, cs, c, f);
  if constexpr (kPointsOnly) return;
  if (intact && t.max_damage > 0) cond->intact[c] = 0;
  store_contact(cs, c, f, t);
  if constexpr (std::is_same_v<Law, BilinearSoftening>) {
    if (cond && cond->damaged_enabled && !cond->intact[c] && cond->eligible[c] && t.outside == 0)
      enter_damaged_condensation(law, in, cs, *cond, c, f);
  }
}

// Contact c's points brought up to the evaluation `in` in the frame stored at it (a damaged
// contact evaluated from its sums there: damaged_condensation.hpp), without turning the frame.
template <typename Law>
inline void catch_up_in_stored_frame(const Law& law, const ContactInputs& in, ContactState& cs,
                                     Index c) {
  const Index a = in.net.particle_a[c], b = in.net.particle_b[c];
  advance_points(law, in, cs, c, contact_frame(in, a, b, cs.normal[c], cs.tangent[c]));
}

// The loop over a network's contacts. With `cond` (the concrete network under BL), an intact
// contact whose points stay below their limits is evaluated from its sums
// (elastic_condensation.hpp) and flagged; the rest go through their points. By blocks of
// consecutive contacts: every contact of a block from its sums in SIMD lanes first, then those
// not intact or near a limit through their points, overwriting what the lanes stored.
//
// `previous` (with `cond`): the last evaluation's kinematics. A contact condensed then and visited
// now first has its points brought up to that step, so that the law sees the history it would
// have had (the dissipation of a point's first inelastic step reads its previous forces). Null
// when the histories are already up to date (the first step after a restart).
template <typename Law>
void evaluate_contacts(const Law& law, const ContactInputs& in, ContactState& cs,
                       ElasticCondensation* cond = nullptr,
                       const ContactInputs* previous = nullptr) {
  if (!cond) {
    parallel_for(in.net.contact_count(), [&](Index c) { evaluate_contact(law, in, cs, cond, c); });
    return;
  }
  assert(in.pose && "the condensed kernel reads the bodies' poses");
  cond->any_condensed = true;  // cleared by the catch-up; harmless if none was
  const CondensedInputs ci{cond->sums, in.net.particle_a.data(), in.net.particle_b.data(), in.pose,
                           in.net.contact_count()};
  parallel_for_blocks(in.net.contact_count(), CondensedBlock::kSize, [&](Index begin, Index end) {
    CondensedBlock block;
    evaluate_condensed_block(ci, begin, end - begin, cs, block);
    for (Index c = begin; c < end; ++c) {
      const bool was_condensed = cond->condensed[c];
      const bool keep = cond->intact[c] && block.below_limits[c - begin];
      cond->condensed[c] = keep;
      if (keep) continue;
      if (was_condensed && previous) evaluate_contact<Law, true>(law, *previous, cs, cond, c);
      if (cond->damaged_active[c]) {
        if (evaluate_damaged_condensed(in, cs, *cond, c)) continue;
        cond->damaged_active[c] = 0;
        if (previous) catch_up_in_stored_frame(law, *previous, cs, c);
      }
      evaluate_contact(law, in, cs, cond, c);
    }
  });
}

// The same from the bodies' state. `rotation`: every body's orientation as a matrix (Simulation
// forms them once per step: a body has about 13 contact ends, and two quaternion-to-matrix
// conversions were a tenth of a contact's cost); formed here when not given (tests).
template <typename Law>
void evaluate_contacts(const Law& law, const ContactNetwork& net, const Bodies& bodies,
                       ContactState& cs, Real dt, const Vec3* anchor0 = nullptr,
                       const Eigen::Matrix3d* rotation = nullptr) {
  std::vector<Eigen::Matrix3d> formed;
  if (!rotation) {
    formed.reserve(bodies.orientation.size());
    for (const Quat& q : bodies.orientation) formed.push_back(q.toRotationMatrix());
    rotation = formed.data();
  }
  const ContactInputs in{net,
                         bodies.position.data(),
                         bodies.position0.data(),
                         bodies.angular_velocity.data(),
                         bodies.orientation0.data(),
                         rotation,
                         anchor0,
                         dt};
  evaluate_contacts(law, in, cs);
}

// Only the damaged contacts in the state (what the strain energy of a history row needs).
template <typename Law>
void catch_up_damaged(const Law& law, const ContactInputs& in, ContactState& cs,
                      const ElasticCondensation& cond) {
  if (cond.damaged_active.empty()) return;
  parallel_for(in.net.contact_count(), [&](Index c) {
    if (cond.damaged_active[c]) catch_up_in_stored_frame(law, in, cs, c);
  });
}

// Brings the histories of the contacts condensed at the last evaluation up to date, from that
// evaluation's kinematics (`in`): what the point loop would have stored (the law's elastic update:
// un, us, fn = kn (un - pn), fs = -ks (us - ps), their maxima). Intact contacts leave the state
// (their sums need no history); damaged ones stay in it, their entry sums unchanged. Changes
// nothing the next steps compute.
template <typename Law>
void catch_up_condensed(const Law& law, const ContactInputs& in, ContactState& cs,
                        ElasticCondensation& cond) {
  if (cond.any_condensed) {
    parallel_for(in.net.contact_count(), [&](Index c) {
      if (!cond.condensed[c]) return;
      evaluate_contact<Law, true>(law, in, cs, &cond, c);
      cond.condensed[c] = 0;
    });
    cond.any_condensed = false;
  }
  catch_up_damaged(law, in, cs, cond);
}

}  // namespace rcdem
