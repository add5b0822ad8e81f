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
// point lies within `radius` of r_c, so |u(r) - u_c| <= |D|_F radius, and the contact is condensed
// only if u_cn + |D|_F radius and |u_c - u_cn n| + |D|_F radius stay below (1 - 1e-3) times the
// smallest elastic limit of its points (fn_max / kn, c_max / ks); the second is tested through
// 2 (|u_c - u_cn n|^2 + (|D|_F radius)^2), a little more cautious and free of square roots. Points
// that would come near a limit send the contact back to the point loop, which finds exactly what it
// would have found had it visited the points every step (the limits are not crossed in between, and
// an intact point's forces do not depend on its stored history). A condensed contact's point
// histories are brought up to date only when someone reads them (Simulation::contacts(): outputs,
// the strain energy, checkpoints), from the kinematics of the step's evaluation.
#include <cstdint>
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// The per-contact sums, read together by the condensed evaluation.
struct CondensedContact {
  Real k_n = 0;     // sum of the points' kn [N/m]
  Real alpha = 0;   // ks / kn, the same at every point
  Real radius = 0;  // max |rho| over the points [m]
  Real u_n0 = 0;    // min fn_max / kn over the points [m]
  Real u_s0 = 0;    // min c_max / ks over the points [m]
  Vec3 centroid;    // r_c, relative to A's centre at t = 0 [m]
  Real j[6] = {};   // J = sum kn rho rho^T: xx, yy, zz, xy, xz, yz [N m]
};

struct ElasticCondensation {
  std::vector<CondensedContact> sums;   // per contact
  std::vector<std::uint8_t> eligible;   // alpha uniform over the contact's points
  std::vector<std::uint8_t> intact;     // every point D = 0 (never set again once cleared)
  std::vector<std::uint8_t> condensed;  // the last evaluation used the sums (histories stale)
  bool any_condensed = false;           // some flag above is set

  // From the network's points and the particles' centres at t = 0; every contact intact.
  static ElasticCondensation build(const ContactNetwork& net, const std::vector<Vec3>& x0);
  // After a restart: intact from the points' damage, nothing condensed.
  void reset_flags(const ContactNetwork& net, const std::vector<Real>& damage);
  Index condensed_count() const;
  Index condensed_point_count(const ContactNetwork& net) const;  // their local points
};

// The condensed evaluation of one contact (formulas above). Returns false, writing nothing, when
// the bound says a point could reach an elastic limit this step.
struct CondensedResult {
  Vec3 force_b, torque_b, torque_a;
};
[[gnu::always_inline]] inline bool evaluate_condensed(const CondensedContact& k, const Vec3& n,
                                                      const Vec3& dx, const Vec3& u0,
                                                      const Eigen::Matrix3d& ra,
                                                      const Eigen::Matrix3d& rb,
                                                      CondensedResult& out) {
  const Eigen::Matrix3d d = rb - ra;
  const Vec3 u_c = u0 + d * k.centroid;
  const Real u_cn = n.dot(u_c);
  // e = |D|_F radius (the Frobenius norm bounds the spectral one), compared squared: the
  // opening u_cn + e < L_n as e^2 < (L_n - u_cn)^2 with L_n > u_cn, the slip |u_s| + e < L_s
  // through (|u_s| + e)^2 <= 2 (|u_s|^2 + e^2) < L_s^2 (no square root on the way).
  const Real spread_sq = d.squaredNorm() * (k.radius * k.radius);
  constexpr Real kMargin = 1.0 - 1e-3;
  const Real room_n = kMargin * k.u_n0 - u_cn;
  if (!(room_n > 0 && spread_sq < room_n * room_n)) return false;
  const Real limit_s = kMargin * k.u_s0;
  if (!(2 * ((u_c - u_cn * n).squaredNorm() + spread_sq) < limit_s * limit_s)) return false;
  const Vec3 f = -k.k_n * (k.alpha * u_c + ((1 - k.alpha) * u_cn) * n);
  const Eigen::Matrix3d s = 0.5 * (ra + rb);
  Eigen::Matrix3d jm;
  jm << k.j[0], k.j[3], k.j[4], k.j[3], k.j[1], k.j[5], k.j[4], k.j[5], k.j[2];
  const Eigen::Matrix3d p = s * (jm * d.transpose());
  const Vec3 axial(p(1, 2) - p(2, 1), p(2, 0) - p(0, 2), p(0, 1) - p(1, 0));
  const Vec3 a_c = 0.5 * u0 + s * k.centroid;
  const Vec3 moment_a = a_c.cross(f) - k.alpha * axial - (1 - k.alpha) * (p * n).cross(n);
  out.force_b = f;
  out.torque_b = moment_a - dx.cross(f);
  out.torque_a = -moment_a;
  return true;
}

}  // namespace rcdem
