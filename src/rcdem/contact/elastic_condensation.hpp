#pragma once
// Intact contacts condensed to a few sums (issue 7).
//
// A local point that has never left the elastic range (D = 0) holds exactly fn = kn u_n and
// fs = -ks u_s (BilinearSoftening::update takes them from the accumulated displacement), and a
// contact's displacement is affine over its facet: u(r) = u0 + (R_B - R_A) r (SPEC 4). So while
// every point of a contact is intact and stays below its elastic limits, the contact's force and
// moment are quadratic forms in its kinematics, and the sums over its 5-8 points reduce to
//   K = sum kn,  the kn-weighted centroid r_c of the points,  J = sum kn rho rho^T (rho = r - r_c)
// with ks = alpha kn at every point of a contact ((4): alpha is a material constant). With
// u_c = u0 + D r_c (D = R_B - R_A), a_c = u0 / 2 + S r_c (S = (R_A + R_B) / 2), u_cn = n . u_c:
//   force on B   F   = -K (alpha u_c + (1 - alpha) u_cn n)
//   moment on B about A's centre
//                M_A = a_c x F - alpha axial(P) - (1 - alpha) (P n) x n,   P = S J D^T,
// axial(P) = (P_yz - P_zy, P_zx - P_xz, P_xy - P_yx): the terms linear in rho vanish because r_c is
// the kn-weighted centroid. That is the point loop's result with no point read or written.
//
// Whether the points stay elastic this step is decided by a bound, not by visiting them: every
// point lies within `radius` of r_c, so |u(r) - u_c| <= |D|_2 radius = e, and the contact is
// condensed only if u_cn + e and |u_c - u_cn n| + e stay below (1 - 1e-3) times the smallest
// elastic limit of its points (fn_max / kn, c_max / ks); the second is tested through
// 2 (|u_c - u_cn n|^2 + e^2), a little more cautious and free of square roots. D being a
// difference of two rotations, |D|_2^2 = |D|_F^2 / 2 exactly (its singular values are
// 2 sin(phi / 2) twice and 0): no root or eigenvalue is needed. (|D|_F, sqrt 2 looser, sends
// intact contacts whose every point is inside back to the point loop.) Points
// that would come near a limit send the contact back to the point loop, which finds exactly what it
// would have found had it visited the points every step (the limits are not crossed in between, and
// an intact point's forces do not depend on its stored history). A condensed contact's point
// histories are brought up to date only when someone reads them (Simulation::contacts(): snapshots,
// checkpoints), from the kinematics of the step's evaluation; the strain energy a history row
// reads comes from the sums (condensed_strain_energy below) and the damage needs nothing (D = 0).
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/held_contacts.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/state/body_poses.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// The per-contact sums, one array per quantity: SIMD lanes load 8 contacts' values at once
// (a record per contact, 17 doubles, defeated GCC's vectoriser).
struct CondensedSums {
  std::vector<Real> k_n;                      // sum of the points' kn [N/m]
  std::vector<Real> alpha;                    // ks / kn, the same at every point
  std::vector<Real> radius;                   // max |rho| over the points [m]
  std::vector<Real> u_n0;                     // min fn_max / kn over the points [m]
  std::vector<Real> u_s0;                     // min c_max / ks over the points [m]
  std::array<std::vector<Real>, 3> centroid;  // r_c, relative to A's centre at t = 0 [m]
  std::array<std::vector<Real>, 3> offset0;   // x_B0 - x_A0 (loaded, not gathered) [m]
  std::array<std::vector<Real>, 6> j;         // J = sum kn rho rho^T: xx, yy, zz, xy, xz, yz [N m]

  static constexpr std::size_t kBytesPerContact = 17 * sizeof(Real);
  bool empty() const { return k_n.empty(); }
  void resize(std::size_t n);
  // Contact i's K, radius, centroid and J (symmetric: its xx, yy, zz, xy, xz, yz kept).
  void set_points(std::size_t i, Real k, Real rad, const Vec3& c, const Eigen::Matrix3d& jm);
};

// A contact's K = sum kn, kn-weighted centroid r_c (relative to A's centre at t = 0, xa0) and
// J = sum kn rho rho^T over its points m in [begin, end) for which carries(m) holds, and the
// radius max |rho| over all of them; kn(m) and position0(m) give a point's normal stiffness and
// position at t = 0. With no point carrying, K = J = 0 and r_c is every point's centroid. The
// condensation's build (every point) and a held contact's broken points (held_contacts.hpp) alike.
template <typename Kn, typename Position0, typename Carries>
void store_point_sums(CondensedSums& sums, std::size_t i, Index begin, Index end, const Vec3& xa0,
                      Kn kn, Position0 position0, Carries carries) {
  Real k_n = 0, k_all = 0;
  Vec3 moment = Vec3::Zero(), moment_all = Vec3::Zero();
  for (Index m = begin; m < end; ++m) {
    const Vec3 r = kn(m) * (position0(m) - xa0);
    k_all += kn(m);
    moment_all += r;
    if (!carries(m)) continue;
    k_n += kn(m);
    moment += r;
  }
  // From the points alone: a value left by an earlier hold would differ after a restart.
  const Vec3 centroid = k_n > 0 ? Vec3(moment / k_n) : Vec3(moment_all / k_all);
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  Real radius = 0;
  for (Index m = begin; m < end; ++m) {
    const Vec3 rho = position0(m) - xa0 - centroid;
    if (carries(m)) j += kn(m) * rho * rho.transpose();
    radius = std::max(radius, rho.norm());
  }
  sums.set_points(i, k_n, radius, centroid, j);
}

struct ElasticCondensation {
  CondensedSums sums;                   // per contact
  std::vector<std::uint8_t> eligible;   // alpha uniform over the contact's points
  std::vector<std::uint8_t> intact;     // every point D = 0 (never set again once cleared)
  std::vector<std::uint8_t> condensed;  // the last evaluation used the sums (histories stale)
  bool any_condensed = false;           // some flag above is set, or a contact is held
  HeldContacts held;                    // damaged contacts held to their sums (held_contacts.hpp)

  // From the network's points and the particles' centres at t = 0; every contact intact.
  static ElasticCondensation build(const ContactNetwork& net, const std::vector<Vec3>& x0);
  // After a restart: intact from the points' damage, nothing condensed or held.
  void reset_flags(const ContactNetwork& net, const PointDamage& damage);
  Index condensed_count() const;
  Index condensed_point_count(const ContactNetwork& net) const;  // their local points
  Index held_point_count(const ContactNetwork& net) const;       // the held contacts' points
};

// The condensed evaluation of a block of consecutive contacts (formulas above), written as plain
// arithmetic on scalars so that GCC runs it in SIMD lanes (8 contacts at a time with AVX-512): the
// bodies' poses are gathered and their rotation matrices rebuilt in the lanes. Every contact of the
// block is computed and its force and torques stored, so no lane branches;
// `below_limits` says which ones the caller may keep (with `intact`); it evaluates the others
// through their points, which overwrites what was stored. A block covers fixed contact numbers, so
// a contact is computed by the same instructions whatever the thread count.
struct CondensedBlock {
  static constexpr Index kSize = 128;
  std::int64_t below_limits[kSize];  // 0 or 1: no point near an elastic limit
};

struct CondensedInputs {
  const CondensedSums& sums;
  const Index* particle_a;
  const Index* particle_b;
  const Real* pose;  // the bodies' centres and orientations at the evaluation (BodyPoses)
  Index contact_count;
  Real* energy = nullptr;  // per contact: where to store each one's elastic energy, if asked
};

// The elastic energy held by condensed contact c's points (sum of kn u_n^2 / 2 + ks |u_s|^2 / 2)
// at the poses of the evaluation that condensed it (BodyPoses of A = particle_a[c] and B), from
// its sums: with u = u_c + D rho over the points and sum kn rho = 0,
//   E = ((1 - alpha) (K u_cn^2 + n^T D J D^T n) + alpha (K |u_c|^2 + tr(D J D^T))) / 2,
// the points' own energy to rounding, without bringing their histories up to date. The same bits
// as the kernel's, which stores it when asked (CondensedInputs::energy).
Real condensed_strain_energy(const CondensedSums& sums, Index c, const Real* pose, Index a,
                             Index b);

// Contacts [begin, begin + count), count <= CondensedBlock::kSize; writes their entries of
// force_b, torque_b, torque_a (not their dissipation: zero, and not read for them).
void evaluate_condensed_block(const CondensedInputs& in, Index begin, Index count, ContactState& cs,
                              CondensedBlock& out);

}  // namespace rcdem
