#pragma once
// Damaged contacts evaluated from sums while every point stays inside its envelope (issue 7).
//
// Once a beam cracks, a quarter of its contacts are damaged, and most of those (60% in the AN4
// beam, bench/RESULTS.md session 10) are not loading their points further: every point unloads
// or reloads inside the BL envelope, with its offsets pn, ps fixed (local_point_state.hpp), so
// its force in the contact's frame is affine in its displacement:
//   phi_m = -kn_m W (v_m - p_m),  W = diag(1, alpha, alpha),  v_m = E^T u_m = c + M rho_m,
// with c = E^T u_c (u_c the displacement at the kn-weighted centroid r_c), M = E^T (R_B - R_A)
// and rho_m = r_m - r_c. Summed over the points (sum kn rho = 0; K, r_c, J as for intact contacts,
// elastic_condensation.hpp):
//   force on B, frame      F = -W (K c - pi),                    pi = sum kn p
//   moment about A, frame  a_c x F + axial(A (G - J M^T W)),     G  = sum kn rho (W p)^T
// with A = E^T (R_A + R_B) / 2, a_c = E^T u0 / 2 + A r_c and axial(X) = (X_12 - X_21, X_20 - X_02,
// X_01 - X_10). pi and G are fixed while the contact stays condensed: 12 numbers instead of the
// points' histories.
//
// Whether every point stays inside is decided by a bound, as for intact contacts. When a contact
// whose points all stayed inside enters, each point's room is the radius of the ball around its
// displacement v (frame components) inside which the law would neither cap it nor grow its damage
// nor raise a maximum that drives damage (bilinear_softening.hpp; u_0 = fn_max / kn, c_max / ks):
//   v_n <= max(un_max, u_n0)                         (no new normal maximum past u_n0)
//   kn (v_n - pn) <= (1 - D) fn_max                   (no tension cap)
//   |v_s| <= max(sqrt(us_max_sq), u_s0)               (no new shear maximum past u_s0)
//   |v_s - ps| <= (1 - D) u_s0 + (mu / alpha) max(0, pn - v_n)  (no shear cap; the friction
//      term loses at most (mu / alpha) |dv| over the ball, hence the division by 1 + mu / alpha)
// less 1e-3 of the point's smaller elastic limit. The contact's room is the least over its points,
// and it stays condensed while |c - c_entry| + |M - M_entry|_F radius stays within it (tested as
// 2 (|dc|^2 + |dM|_F^2 radius^2) <= room^2, a little more cautious and free of square roots):
// every point's displacement then lies in its ball. The frame still turns every step (SPEC 4);
// the offsets are carried in it like the histories they are.
//
// A contact leaving the state has its points brought up to the last evaluation in the frame
// stored there (contact_loop.hpp, catch_up_in_stored_frame): the law's elastic update, offsets
// and damage unchanged, so the point loop then sees exactly the history it would have had. Reads
// of the state do the same without ending the state (pi and G stay valid), so reading changes
// nothing that follows. The entry values are saved in checkpoints (condensation.damaged), so a
// restart continues bitwise.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rcdem/contact/contact_frame.hpp"
#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/contact/laws/bilinear_softening.hpp"

namespace rcdem {

// Contact c, just advanced through its points in frame f with every point inside its envelope:
// enters the state if its room is positive (the bound above).
inline void enter_damaged_condensation(const BilinearSoftening& law, const ContactInputs& in,
                                       const ContactState& cs, ElasticCondensation& cond, Index c,
                                       const ContactFrame& f) {
  const ContactNetwork& net = in.net;
  const auto i = static_cast<std::size_t>(c);
  const CondensedSums& k = cond.sums;
  const Real alpha = k.alpha[i];
  const Real mu_ratio = law.mu_c / alpha;
  const Vec3 rc(k.centroid[0][i], k.centroid[1][i], k.centroid[2][i]);
  const Vec3 xa0 = in.x0[net.particle_a[c]];
  const LocalPointArrays& p = cs.point;
  Real room = std::numeric_limits<Real>::infinity();
  Vec3 pi = Vec3::Zero();
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
    const LocalPointConstants& kc = net.constants[m];
    const Real u_n0 = kc.fn_max / kc.kn, u_s0 = kc.c_max / kc.ks;
    const Real d = p.damage[m], vn = p.un[m], v1 = p.us1[m], v2 = p.us2[m];
    const Real pn = p.pn[m], p1 = p.ps1[m], p2 = p.ps2[m];
    const Real r_max_n = std::max(p.un_max[m], u_n0) - vn;
    const Real r_cap_n = (1 - d) * u_n0 + pn - vn;
    const Real r_max_s = std::max(std::sqrt(p.us_max_sq[m]), u_s0) - std::hypot(v1, v2);
    const Real r_cap_s =
        ((1 - d) * u_s0 + mu_ratio * std::max<Real>(0, pn - vn) - std::hypot(v1 - p1, v2 - p2)) /
        (1 + mu_ratio);
    room = std::min({room, r_max_n, r_cap_n, r_max_s, r_cap_s}) - 1e-3 * std::min(u_n0, u_s0);
    const Vec3 rho = net.point_position0[m] - xa0 - rc;
    pi += kc.kn * Vec3(pn, p1, p2);
    g += kc.kn * rho * Vec3(pn, alpha * p1, alpha * p2).transpose();
  }
  if (!(room > 0)) return;  // also a NaN limit
  DamagedSums& e = cond.damaged[i];
  e.room = room;
  const Vec3 cc = f.disp0 + f.disp * rc;
  for (int r = 0; r < 3; ++r) {
    e.c[r] = cc[r];
    e.pi[r] = pi[r];
    for (int q = 0; q < 3; ++q) {
      e.m[3 * r + q] = f.disp(r, q);
      e.g[3 * r + q] = g(r, q);
    }
  }
  cond.damaged_active[i] = 1;
}

// Contact c in the state, at evaluation `in`: if the bound holds, its force, torques and zero
// dissipation are stored from its sums (formulas above), the frame turned, and true returned;
// otherwise nothing is changed and false returned (the caller catches its points up and sends it
// through them).
inline bool evaluate_damaged_condensed(const ContactInputs& in, ContactState& cs,
                                       const ElasticCondensation& cond, Index c) {
  const auto i = static_cast<std::size_t>(c);
  const CondensedSums& k = cond.sums;
  const DamagedSums& e = cond.damaged[i];
  const Index a = in.net.particle_a[c], b = in.net.particle_b[c];
  const Vec3 n = contact_normal(in, a, b, c);
  const Vec3 t1 = turned_frame_axis(in, cs, a, b, c, n);
  const ContactFrame f = contact_frame(in, a, b, n, t1);
  const Vec3 rc(k.centroid[0][i], k.centroid[1][i], k.centroid[2][i]);
  const Vec3 cc = f.disp0 + f.disp * rc;
  Real dc2 = 0, dm2 = 0;
  for (int r = 0; r < 3; ++r) {
    dc2 += (cc[r] - e.c[r]) * (cc[r] - e.c[r]);
    for (int q = 0; q < 3; ++q) dm2 += (f.disp(r, q) - e.m[3 * r + q]) * (f.disp(r, q) - e.m[3 * r + q]);
  }
  const Real radius = k.radius[i];
  if (!(2 * (dc2 + dm2 * radius * radius) <= e.room * e.room)) return false;

  const Real kk = k.k_n[i], alpha = k.alpha[i];
  PointTotals t;
  t.phi_n = -(kk * cc[0] - e.pi[0]);
  t.phi_1 = -alpha * (kk * cc[1] - e.pi[1]);
  t.phi_2 = -alpha * (kk * cc[2] - e.pi[2]);
  Eigen::Matrix3d j;
  j << k.j[0][i], k.j[3][i], k.j[4][i], k.j[3][i], k.j[1][i], k.j[5][i], k.j[4][i], k.j[5][i],
      k.j[2][i];
  Eigen::Matrix3d h;  // G - J M^T W: reference rows, frame columns
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) h(r, q) = e.g[3 * r + q];
  Eigen::Matrix3d jmt = j * f.disp.transpose();
  jmt.col(1) *= alpha;
  jmt.col(2) *= alpha;
  h -= jmt;
  const Eigen::Matrix3d x = f.arm * h;
  const Vec3 phi(t.phi_n, t.phi_1, t.phi_2);
  const Vec3 a_c = 0.5 * f.disp0 + f.arm * rc;
  const Vec3 mom = a_c.cross(phi) + Vec3(x(1, 2) - x(2, 1), x(2, 0) - x(0, 2), x(0, 1) - x(1, 0));
  t.mom_n = mom[0];
  t.mom_1 = mom[1];
  t.mom_2 = mom[2];
  cs.normal[c] = n;
  cs.tangent[c] = t1;
  store_contact(cs, c, f, t);
  return true;
}

}  // namespace rcdem
