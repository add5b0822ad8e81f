#pragma once
// The loop over contacts and their local points, written once for every law (the law is a
// template parameter, chosen once per step). Each contact writes only its own outputs, so the
// loop runs in parallel and the result does not depend on the thread count.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "rcdem/contact/contact_frame.hpp"
#include "rcdem/contact/contact_kinematics.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/contact/held_contacts.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
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
  // 1 where this step took the point's D from 0 above 0, or from below 1 to 1 (D never decreases,
  // S4): what the step's counters of damaged and broken points add (as reals, to be summed in
  // the SIMD reduction).
  Real newly_damaged = 0, newly_broken = 0;
};

// One local point of a contact, in the contact's frame (see evaluate_contacts): advances its
// history by the law and returns what it adds to the contact's sums. A point is read from and
// written to its record (local_point_records.hpp). BL's branches keep the loop over a contact's
// points scalar, and that is the faster form: a branch-free elastic pass in SIMD lanes with a
// scalar pass for the points that leave the elastic range, a full 8-lane pass with idle lanes
// masked, and the law written with selects in one vector per contact were all slower
// (bench/RESULTS.md): every lane then pays both divisions and both roots.
template <typename Law>
struct PointUpdate {
  const Law& law;
  LocalPointRecord* records;
  Vec3 xa0;              // A's centre at t = 0
  Vec3 disp0;            // E^T u0
  Eigen::Matrix3d disp;  // E^T (R_B - R_A)
  Eigen::Matrix3d arm;   // E^T (R_A + R_B) / 2

  [[gnu::always_inline]] PointSums operator()(Index m) const {
    LocalPointRecord& p = records[m];
    const Real rx = p.x0 - xa0.x(), ry = p.y0 - xa0.y(), rz = p.z0 - xa0.z();
    // Total displacement in the frame: opening along n, shear along t1, t2.
    const Real u_n = disp0.x() + disp(0, 0) * rx + disp(0, 1) * ry + disp(0, 2) * rz;
    const Real u_1 = disp0.y() + disp(1, 0) * rx + disp(1, 1) * ry + disp(1, 2) * rz;
    const Real u_2 = disp0.z() + disp(2, 0) * rx + disp(2, 1) * ry + disp(2, 2) * rz;
    typename Law::template State<PlaneVec> s = p.history;
    const Real damage_before = s.damage;
    const LawResult res = law.update(p.constants, s, u_n, PlaneVec{u_1, u_2});  // (1)-(2)
    store_state(p.history, s);
    PointSums out;
    out.point_damage = s.damage;
    out.newly_damaged = damage_before == 0 && s.damage > 0;
    out.newly_broken = damage_before < 1 && s.damage >= 1;
    // On B; tension (fn > 0) pulls B back towards A.
    out.f_n = -s.fn;
    out.f_1 = s.fs.x;
    out.f_2 = s.fs.y;
    out.damage = res.dissipated - res.dissipated_friction;
    out.friction = res.dissipated_friction;
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

// What the evaluation of a network's contacts reads in one step.
struct ContactInputs {
  const ContactNetwork& net;
  const Vec3* x;                    // body centres at the evaluation
  const Vec3* x0;                   // at t = 0
  const Vec3* w;                    // angular velocities
  const Quat* q0;                   // orientations at t = 0
  const Eigen::Matrix3d* rotation;  // orientations as matrices
  const Vec3* anchor0;              // interface contacts only (below), else null
  Real dt;
  const Real* pose = nullptr;  // BodyPoses of x and the orientations: needed with condensation
};

// Body i's centre and orientation at the evaluation: from its pose when the inputs have them (one
// cache line per body, which the condensed kernel has just read for the block, where the centre
// and the matrix are three lines elsewhere), else from the arrays. The same bits either way
// (rotation_from_quaternion is toRotationMatrix's arithmetic; the golden cases are unchanged).
[[gnu::always_inline]] inline Vec3 body_centre(const ContactInputs& in, Index i) {
  if (!in.pose) return in.x[i];
  const Real* p = in.pose + BodyPoses::kStride * i;
  return Vec3(p[0], p[1], p[2]);
}
[[gnu::always_inline]] inline Eigen::Matrix3d body_rotation(const ContactInputs& in, Index i) {
  if (!in.pose) return in.rotation[i];
  const Real* p = in.pose + BodyPoses::kStride * i;
  Real r[9];
  rotation_from_quaternion(p[3], p[4], p[5], p[6], r);
  return Eigen::Map<const Eigen::Matrix3d>(r);
}

// With `anchor0` (steel-concrete interface contacts, SPEC 8), B is a cylinder and the normal is the
// component of (x_A - anchor) perpendicular to the cylinder's current axis, pointing from A to the
// axis, anchor being the interface sphere's centre carried by the cylinder: the sphere
// discretisation then adds no artificial interlock along the bar.
[[gnu::always_inline]] inline Vec3 contact_normal(const ContactInputs& in, Index a, Index b,
                                                  Index c) {
  if (in.anchor0) {
    const Eigen::Matrix3d& rb = in.rotation[b];
    const Vec3 axis = rb * (in.q0[b] * Vec3::UnitZ());
    const Vec3 anchor = in.x[b] + rb * (in.anchor0[c] - in.x0[b]);
    const Vec3 d = anchor - in.x[a];
    return (d - d.dot(axis) * axis).normalized();
  }
  // Eigen's normalized() of this expression was not inlined: a call per contact, in the hot loop.
  const Vec3 d = body_centre(in, b) - body_centre(in, a);
  return d / std::sqrt(d.squaredNorm());  // the same rounding as normalized()
}

// The frame's axes n, t1 at this evaluation, turned from the stored ones (not yet stored: a held
// contact, held_contacts.hpp, needs the stored frame if it has to catch up).
[[gnu::always_inline]] inline void turned_frame(const ContactInputs& in, const ContactState& cs,
                                                const ElasticCondensation* cond, Index c,
                                                ContactFrame& f) {
  const Index a = in.net.particle_a[c];
  const Index b = in.net.particle_b[c];
  const Vec3 n = contact_normal(in, a, b, c);
  f.intact = cond && cond->intact[c];
  Vec3 t1;
  if (f.intact) {
    t1 = any_perpendicular(n);
  } else {
    // SPEC 4: the plane's frame turns with the contact, carrying every point's shear history.
    const PlaneRotation rot{cs.normal[c], n, 0.5 * in.dt * (in.w[a] + in.w[b]).dot(n)};
    t1 = rot.turn_frame_axis(cs.tangent[c]);
    if (!(t1.squaredNorm() > 0.5)) t1 = any_perpendicular(n);  // only after a turn near 90 deg
  }
  f.n = n;
  f.t1 = t1;
}

// The rest of the frame from its axes f.n, f.t1 and the kinematics `in`.
[[gnu::always_inline]] inline void frame_kinematics(const ContactInputs& in,
                                                    const ElasticCondensation* cond, Index c,
                                                    ContactFrame& f) {
  const Index a = in.net.particle_a[c];
  const Index b = in.net.particle_b[c];
  f.t2 = f.n.cross(f.t1);
  Eigen::Matrix3d frame_t;  // E^T: rows n, t1, t2
  frame_t.row(0) = f.n.transpose();
  frame_t.row(1) = f.t1.transpose();
  frame_t.row(2) = f.t2.transpose();
  const Eigen::Matrix3d ra = body_rotation(in, a);
  const Eigen::Matrix3d rb = body_rotation(in, b);
  f.dx = body_centre(in, b) - body_centre(in, a);
  // x_B0 - x_A0: from the condensation's sums when there are some (the same bits, and in cache,
  // where B's centre at t = 0 is a line of its own).
  const Vec3 r0 =
      cond ? Vec3(cond->sums.offset0[0][c], cond->sums.offset0[1][c], cond->sums.offset0[2][c])
           : Vec3(in.x0[b] - in.x0[a]);
  Vec3 u0;
  for (int i = 0; i < 3; ++i)
    u0[i] = offset_displacement(f.dx[i], rb(i, 0), rb(i, 1), rb(i, 2), r0.x(), r0.y(), r0.z());
  f.disp = frame_t * (rb - ra);
  f.disp0 = frame_t * u0;
  f.arm = frame_t * (0.5 * (ra + rb));
  f.xa0 = in.x0[a];
}

[[gnu::always_inline]] inline void contact_frame(const ContactInputs& in, ContactState& cs,
                                                 const ElasticCondensation* cond, Index c,
                                                 ContactFrame& f) {
  turned_frame(in, cs, cond, c, f);
  cs.normal[c] = f.n;
  cs.tangent[c] = f.t1;
  frame_kinematics(in, cond, c, f);
}

// Asks for the cache lines that hold elements [begin, end) of an array (kWrite: to be written)
// into L1, or with kLocality 2 into L2.
template <int kWrite, typename T, int kLocality = 3>
[[gnu::always_inline]] inline void prefetch_elements(const T* p, Index begin, Index end) {
  const char* lo = reinterpret_cast<const char*>(p + begin);
  const char* hi = reinterpret_cast<const char*>(p + end) - 1;
  for (const char* q = lo; q < hi; q += 64) __builtin_prefetch(q, kWrite, kLocality);
  __builtin_prefetch(hi, kWrite, kLocality);
}

// Contact c's points' records, requested while the block forms its frames: the damaged contacts
// of a block lie scattered among condensed ones, so no hardware prefetcher follows them, and the
// first touch of each one's points is the point path's largest cost (bench/RESULTS.md). For
// writing: every visit writes the records' second lines.
[[gnu::always_inline]] inline void prefetch_points(const ContactNetwork& net,
                                                   const LocalPointRecords& records, Index c) {
  prefetch_elements<1>(records.data(), net.point_begin[c], net.point_begin[c + 1]);
}

// The points of contact c in its frame `f`, and what the contact then exerts: the second half.
// Returns how many of its points became damaged and broken.
template <typename Law, bool kPointsOnly = false>
[[gnu::always_inline]] inline PointTransitions contact_points(const Law& law,
                                                              const ContactInputs& in,
                                                              ContactState& cs,
                                                              ElasticCondensation* cond, Index c,
                                                              const ContactFrame& f) {
  const ContactNetwork& net = in.net;
  Real phi_n = 0.0, phi_1 = 0.0, phi_2 = 0.0, mom_n = 0.0, mom_1 = 0.0, mom_2 = 0.0;
  Real damage = 0.0, friction = 0.0, max_damage = 0.0, newly_damaged = 0.0, newly_broken = 0.0;
  const PointUpdate<Law> point{law, cs.point.data(), f.xa0, f.disp0, f.disp, f.arm};
  const Index begin = net.point_begin[c], end = net.point_begin[c + 1];
#pragma omp simd reduction(+ : phi_n, phi_1, phi_2, mom_n, mom_1, mom_2, damage, friction, \
                               newly_damaged, newly_broken) reduction(max : max_damage)
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
    newly_damaged += o.newly_damaged;
    newly_broken += o.newly_broken;
    max_damage = std::max(max_damage, o.point_damage);
  }
  const PointTransitions changed{static_cast<Index>(newly_damaged),
                                 static_cast<Index>(newly_broken)};
  if constexpr (kPointsOnly) return changed;
  if (f.intact && max_damage > 0) cond->intact[c] = 0;
  const Vec3 force = phi_n * f.n + phi_1 * f.t1 + phi_2 * f.t2;
  const Vec3 moment_a = mom_n * f.n + mom_1 * f.t1 + mom_2 * f.t2;
  cs.force_b[c] = force;
  cs.torque_b[c] = moment_a - f.dx.cross(force);
  cs.torque_a[c] = -moment_a;
  cs.dissipated_damage[c] = damage;
  cs.dissipated_friction[c] = friction;
  return changed;
}

// One contact through its points (kPointsOnly: only the points' histories and the frame, for
// ElasticCondensation's catch-up; nothing the gather reads).
//
// Everything per point is done in the contact's frame E = [n t1 t2] (right-handed: t2 = n x t1),
// with matrices formed once per contact, so that a point costs two 3x3 products, the law and a
// cross product, all on plain scalars (in SIMD lanes for the EL law, see PointUpdate):
//   relative displacement (SPEC 4, contact_kinematics.hpp): u_J = u0 + (R_B - R_A) r,
//     r = p_J0 - x_A0, so in the frame E^T u_J = E^T u0 + (E^T (R_B - R_A)) r;
//   force on B in the frame: phi = (-fn, fs1, fs2), the contact's force E sum(phi);
//   the point's position relative to A's centre, x_A + R_A r + u_J / 2 - x_A, in the frame
//     rho = E^T u0 / 2 + (E^T (R_A + (R_B - R_A) / 2)) r, and the moment about A
//     sum (E rho) x (E phi) = E sum(rho x phi) (E is a rotation).
// The frame turns with the contact (SPEC 4), carrying the points' shear histories, except while
// every point of the contact is intact: their forces are then independent of the frame
// (kn u_n, -ks u_s), so it is any axis across n, as ElasticCondensation's catch-up draws it.
template <typename Law, bool kPointsOnly = false>
[[gnu::always_inline]] inline PointTransitions evaluate_contact(
    const Law& law, const ContactInputs& in, ContactState& cs, ElasticCondensation* cond, Index c) {
  ContactFrame f;
  contact_frame(in, cs, cond, c, f);
  return contact_points<Law, kPointsOnly>(law, in, cs, cond, c, f);
}

// Brings held contact c's points up to the evaluation `in` (the last one that held it), in the
// frame stored by that evaluation.
template <typename Law>
void catch_up_held(const Law& law, const ContactInputs& in, ContactState& cs,
                   ElasticCondensation& cond, Index c) {
  ContactFrame f;
  f.n = cs.normal[c];
  f.t1 = cs.tangent[c];
  f.intact = false;
  frame_kinematics(in, &cond, c, f);
  contact_points<Law, true>(law, in, cs, &cond, c, f);
}

// Releases held contact c, its points brought up to the last evaluation `in` from their histories
// at entry (put back first if a read saved them), unless a read since that evaluation has done so.
template <typename Law>
void release_held(const Law& law, const ContactInputs& in, ContactState& cs,
                  ElasticCondensation& cond, Index c) {
  HeldContacts& h = cond.held;
  const Index begin = in.net.point_begin[c];
  h.take_entry(c, h.current ? nullptr : cs.point.data() + begin, in.net.point_begin[c + 1] - begin);
  if (!h.current) catch_up_held(law, in, cs, cond, c);
  h.held[static_cast<std::size_t>(c)] = 0;
}

// The elastic energies of the visited contacts `visit[0, count)`, from their points, just after
// the block evaluated them. Out of line, so that the loop's own function stays small enough for
// GCC to inline the point loop's Eigen operations (regression.hot_loop_inlined; CMakeLists.txt).
template <typename Law>
[[gnu::noinline]] void keep_point_energies(const Law& law, const ContactNetwork& net,
                                           const ContactState& cs, const Index* visit, Index count,
                                           Real* energy) {
  for (Index k = 0; k < count; ++k) energy[visit[k]] = cs.strain_energy(law, net, visit[k]);
}

// A block's transitions (PointTransitions), and the flag of each contact with a newly broken
// point, which ContactState::tally_transitions collects after the loop.
[[gnu::always_inline]] inline void note_transitions(ContactState& cs, Index c,
                                                    const PointTransitions& t,
                                                    PointTransitions& sum) {
  sum.damaged += t.damaged;
  sum.broken += t.broken;
  if (t.broken > 0) cs.newly_broken_contact[static_cast<std::size_t>(c)] = 1;
}

// A softening hold's clock (HeldContacts::softening_clock): a step held, and the hold's end, after
// which a short hold makes its contact wait.
[[gnu::always_inline]] inline void count_softening_step(HeldContacts& h, Index c) {
  std::int16_t& clock = h.softening_clock[static_cast<std::size_t>(c)];
  if (clock < kShortSofteningHold) ++clock;
}
[[gnu::always_inline]] inline void end_softening_hold(HeldContacts& h, Index c) {
  std::int16_t& clock = h.softening_clock[static_cast<std::size_t>(c)];
  clock = clock < kShortSofteningHold ? static_cast<std::int16_t>(-kSofteningBackoff) : 0;
}

// The held contacts `held[0, count)` of the block from `begin` (held_contacts.hpp): from their
// sums in SIMD lanes while their points stay inside their rooms. The others have their points
// brought up to the last evaluation (`previous`) in the stored frame, are released, get their
// frame in `frames[c - begin]` and join the visited ones `visit[0, visits)`, kept in contact order
// (the block's dissipation is summed in that order). Returns the new count of visits; adds the
// energy the kept ones' softening points dissipate to `damage`, in list order.
template <typename Law>
[[gnu::noinline]] Index evaluate_held_contacts(const Law& law, const ContactInputs& in,
                                               const ContactInputs& previous, ContactState& cs,
                                               ElasticCondensation& cond, const Index* held,
                                               Index count, ContactFrame* frames, Index begin,
                                               Real* energy, Index* visit, Index visits,
                                               Real& damage) {
  HeldSums* block_sums = &cond.held.sums(begin);  // the block's, by c - begin
  const HeldInputs hi{cond.sums,
                      in.net.particle_a.data(),
                      in.net.particle_b.data(),
                      in.pose,
                      in.w->data(),
                      cs.normal.data()->data(),
                      cs.tangent.data()->data(),
                      in.dt,
                      reinterpret_cast<const Real*>(block_sums),
                      begin};
  HeldOutputs out;
  evaluate_held_block(hi, held, count, energy != nullptr, out);
  const Index visited = visits;
  for (Index k = 0; k < count; ++k) {
    const Index c = held[k];
    if (out.kept[k]) {
      cs.force_b[c] = Vec3(out.force[0][k], out.force[1][k], out.force[2][k]);
      cs.torque_b[c] = Vec3(out.torque_b[0][k], out.torque_b[1][k], out.torque_b[2][k]);
      cs.torque_a[c] = Vec3(out.torque_a[0][k], out.torque_a[1][k], out.torque_a[2][k]);
      cs.normal[c] = Vec3(out.n[0][k], out.n[1][k], out.n[2][k]);
      cs.tangent[c] = Vec3(out.t1[0][k], out.t1[1][k], out.t1[2][k]);
      cs.dissipated_damage[c] = out.dissipated[k];
      cs.dissipated_friction[c] = 0.0;
      damage += out.dissipated[k];
      if (energy) energy[c] = out.energy[k];
      HeldSums& h = block_sums[c - begin];
      if (h.open_margin >= 0) {  // with broken points: this step is the next one's last
        h.last_du_n = out.du_n[k];
        for (int e = 0; e < 3; ++e) h.last_dd_n[e] = out.dd_n[e][k];
      }
      if (h.slope_n < 0) count_softening_step(cond.held, c);
      continue;
    }
    prefetch_points(in.net, cs.point, c);
    if (block_sums[c - begin].slope_n < 0) end_softening_hold(cond.held, c);
    release_held(law, previous, cs, cond, c);
    contact_frame(in, cs, &cond, c, frames[c - begin]);
    visit[visits++] = c;
  }
  if (visits > visited) std::sort(visit, visit + visits);
  return visits;
}

// What the held contacts' kernel will read of the block from `begin` outside the block's own
// data (its held contacts' sums, both ends' spins, the stored frames), and the dissipation it
// writes, requested into L2 once this block's held contacts are done: this thread most likely
// evaluates that block next, and the requests have this block's points and the next block's
// condensed contacts to arrive in. Asked for within the block itself, before its kernel, they
// came too late for it to find them, and a pass that loaded them there waited on each line
// (bench/RESULTS.md).
[[gnu::always_inline]] inline void prefetch_held_sums(const ElasticCondensation& cond, Index begin,
                                                      Index contacts, const ContactInputs& in,
                                                      const ContactState& cs) {
  const HeldContacts& h = cond.held;
  const auto b = static_cast<std::size_t>(begin / HeldContacts::kBlock);
  if (begin >= contacts || h.block[b].empty()) return;
  const Index end = std::min(begin + HeldContacts::kBlock, contacts);
  constexpr int kL2 = 2;
  // The held contacts' dissipation is written into lines the condensed kernel does not touch.
  prefetch_elements<1, Real, kL2>(cs.dissipated_damage.data(), begin, end);
  prefetch_elements<1, Real, kL2>(cs.dissipated_friction.data(), begin, end);
  for (Index c = begin; c < end; ++c) {
    if (!h.held[static_cast<std::size_t>(c)]) continue;
    prefetch_elements<0, HeldSums, kL2>(h.block[b].data(), c - begin, c - begin + 1);
    __builtin_prefetch(in.w + in.net.particle_b[c], 0, 2);
    __builtin_prefetch(in.w + in.net.particle_a[c], 0, 2);
    __builtin_prefetch(cs.normal.data() + c, 0, 2);
    __builtin_prefetch(cs.tangent.data() + c, 0, 2);
  }
}

// The visited contacts `visit[0, count)` of the block from `begin`, just evaluated in their frames
// `frames[c - begin]`, that are damaged (or intact, with HeldContacts::intact) and have every point
// inside its room are held from the next step (hold_contact; u_nu > 0: softening points too,
// unless the contact's softening clock makes it wait: each visit then counts one off).
[[gnu::noinline]] inline void hold_visited_contacts(const ContactInputs& in, const ContactState& cs,
                                                    ElasticCondensation& cond, const Index* visit,
                                                    Index count, const ContactFrame* frames,
                                                    Index begin, Real u_nu) {
  const ContactNetwork& net = in.net;
  for (Index k = 0; k < count; ++k) {
    const Index c = visit[k];
    if (!cond.eligible[c] || (cond.intact[c] && !cond.held.intact)) continue;
    Real soften = u_nu;
    if (u_nu > 0) {
      std::int16_t& clock = cond.held.softening_clock[static_cast<std::size_t>(c)];
      if (clock < 0) {
        ++clock;
        soften = 0.0;
      }
    }
    HeldSums h;
    if (hold_contact(cond.sums, c, frames[c - begin], in.pose, net.particle_a[c], net.particle_b[c],
                     cs.point.data(), net.point_begin[c], net.point_begin[c + 1], soften, h)) {
      cond.held.sums(c) = h;
      cond.held.held[c] = 1;
    }
  }
}

// The loop over a network's contacts. With `cond` (the concrete network under BL), an intact
// contact whose points stay below their limits is evaluated from its sums
// (elastic_condensation.hpp) and flagged; the rest go through their points. By blocks of
// consecutive contacts: every contact of a block from its sums in SIMD lanes first, then those
// not intact or near a limit through their points, overwriting what the lanes stored.
//
// `previous` (with `cond`): the last evaluation's kinematics. A contact condensed then and visited
// now first has its points brought up to that step, so that the law sees the history it would
// have had (the dissipation of a point's first inelastic step reads its previous forces).
//
// Every contact's point transitions are counted per block of CondensedBlock::kSize contacts
// (ContactState::block_transitions), with or without `cond`. With `cond` and `energy` (per
// contact), each contact's elastic energy after the evaluation is stored there, while its data are
// in cache: a condensed one's by the kernel (condensed_strain_energy's bits), the others' from
// their points (ContactState::strain_energy). Without `cond` it is not (a run then sums the
// energy after the step, as a pass over the contacts).
template <typename Law>
void evaluate_contacts(const Law& law, const ContactInputs& in, ContactState& cs,
                       ElasticCondensation* cond = nullptr, const ContactInputs* previous = nullptr,
                       Real* energy = nullptr) {
  constexpr Index kBlock = CondensedBlock::kSize;
  cs.size_blocks(in.net.contact_count(), kBlock);
  if (!cond) {
    parallel_for_listed_blocks(
        cs.evaluated(), in.net.contact_count(), kBlock, [&](Index begin, Index end) {
          PointTransitions sum;
          for (Index c = begin; c < end; ++c)
            note_transitions(cs, c, evaluate_contact(law, in, cs, cond, c), sum);
          cs.block_transitions[static_cast<std::size_t>(begin / kBlock)] = sum;
        });
    cs.tally_transitions(kBlock);
    return;
  }
  assert(in.pose && "the condensed kernel reads the bodies' poses");
  cond->any_condensed = true;  // cleared by the catch-up; harmless if none was
  const CondensedInputs ci{cond->sums, in.net.particle_a.data(), in.net.particle_b.data(),
                           in.pose,    in.net.contact_count(),   energy};
  const Index blocks = (in.net.contact_count() + kBlock - 1) / kBlock;
  if (static_cast<Index>(cs.block_damage.size()) != blocks) {  // the first step only
    cs.block_damage.assign(static_cast<std::size_t>(blocks), 0.0);
    cs.block_friction.assign(static_cast<std::size_t>(blocks), 0.0);
  }
  parallel_for_listed_blocks(
      cs.evaluated(), in.net.contact_count(), kBlock, [&](Index begin, Index end) {
        CondensedBlock block;
        evaluate_condensed_block(ci, begin, end - begin, cs, block);
        // The contacts that go through their points form their frames first (by c - begin); the
        // held ones are listed, then evaluated together in SIMD lanes (those that leave their room
        // join the visited ones); then every visited contact's points.
        Index visit[CondensedBlock::kSize], held[CondensedBlock::kSize];
        ContactFrame frames[CondensedBlock::kSize];
        Index visits = 0, helds = 0;
        Real held_damage = 0.0;
        for (Index c = begin; c < end; ++c) {
          const bool was_condensed = cond->condensed[c];
          // An intact contact held (HeldContacts::intact) stays held until it leaves its room.
          const bool keep = cond->intact[c] && block.below_limits[c - begin] && !cond->held.held[c];
          cond->condensed[c] = keep;
          if (keep) continue;
          if (was_condensed) evaluate_contact<Law, true>(law, *previous, cs, cond, c);
          if (kHoldableLaw<Law> && cond->held.held[c]) {  // its frame comes with its sums
            held[helds++] = c;
            continue;
          }
          prefetch_points(in.net, cs.point, c);
          contact_frame(in, cs, cond, c, frames[c - begin]);
          visit[visits++] = c;
        }
        if constexpr (kHoldableLaw<Law>)
          if (helds > 0)
            visits = evaluate_held_contacts(law, in, *previous, cs, *cond, held, helds, frames,
                                            begin, energy, visit, visits, held_damage);
        if constexpr (kHoldableLaw<Law>)
          prefetch_held_sums(*cond, begin + kBlock, in.net.contact_count(), in, cs);
        PointTransitions changed;
        for (Index k = 0; k < visits; ++k)
          note_transitions(cs, visit[k],
                           contact_points(law, in, cs, cond, visit[k], frames[visit[k] - begin]),
                           changed);
        if constexpr (kHoldableLaw<Law>)
          if (cond->held.enabled)
            hold_visited_contacts(in, cs, *cond, visit, visits, frames, begin,
                                  cond->held.softening ? law.u_nu() : 0.0);
        if (energy) keep_point_energies(law, in.net, cs, visit, visits, energy);
        cs.block_transitions[static_cast<std::size_t>(begin / kBlock)] = changed;
        // Contacts evaluated from the condensation's sums dissipate exactly zero, so that kernel
        // does not store it (16 bytes a contact less to write) and the block sums its visited
        // contacts, in contact order, then adds what its held ones' softening points dissipated.
        Real damage = 0.0, friction = 0.0;
        for (Index k = 0; k < visits; ++k) {
          damage += cs.dissipated_damage[visit[k]];
          friction += cs.dissipated_friction[visit[k]];
        }
        damage += held_damage;
        cs.block_damage[begin / CondensedBlock::kSize] = damage;
        cs.block_friction[begin / CondensedBlock::kSize] = friction;
      });
  cond->held.current = false;
  cs.tally_transitions(kBlock);
}

// A network's inputs from the bodies' current state (`rotation`: their orientations as matrices).
inline ContactInputs body_inputs(const ContactNetwork& net, const Bodies& bodies,
                                 const Eigen::Matrix3d* rotation, const Vec3* anchor0, Real dt) {
  return {net,
          bodies.position.data(),
          bodies.position0.data(),
          bodies.angular_velocity.data(),
          bodies.orientation0.data(),
          rotation,
          anchor0,
          dt};
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
  evaluate_contacts(law, body_inputs(net, bodies, rotation, anchor0, dt), cs);
}

// Brings the histories of the contacts condensed at the last evaluation up to date, from that
// evaluation's kinematics (`in`): what the point loop would have stored (the law's elastic update:
// un, us, fn = kn un, fs = -ks us, their maxima); and the held contacts' from their entry's,
// which stay held (held_contacts.hpp). Changes nothing the next steps compute.
template <typename Law>
void catch_up_condensed(const Law& law, const ContactInputs& in, ContactState& cs,
                        ElasticCondensation& cond) {
  if (!cond.any_condensed) return;
  HeldContacts& h = cond.held;
  const bool catch_up_held_ones = kHoldableLaw<Law> && !h.current;
  if (catch_up_held_ones) h.keep_entries(in.net.point_begin.data(), cs.point.data());
  parallel_for(in.net.contact_count(), [&](Index c) {
    if (catch_up_held_ones && h.held[c]) catch_up_held(law, in, cs, cond, c);
    if (!cond.condensed[c]) return;
    evaluate_contact<Law, true>(law, in, cs, &cond, c);
    cond.condensed[c] = 0;
  });
  h.current = true;
  cond.any_condensed = false;
}

}  // namespace rcdem
