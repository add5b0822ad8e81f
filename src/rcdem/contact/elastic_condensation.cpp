#include "rcdem/contact/elastic_condensation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rcdem/contact/contact_kinematics.hpp"
#include "rcdem/core/simd_level.hpp"

namespace rcdem {

void CondensedSums::resize(std::size_t n) {
  for (std::vector<Real>* v : {&k_n, &alpha, &radius, &u_n0, &u_s0}) v->assign(n, 0.0);
  for (auto& v : centroid) v.assign(n, 0.0);
  for (auto& v : offset0) v.assign(n, 0.0);
  for (auto& v : j) v.assign(n, 0.0);
}

void CondensedSums::set_points(std::size_t i, Real k, Real rad, const Vec3& c,
                               const Eigen::Matrix3d& jm) {
  k_n[i] = k;
  radius[i] = rad;
  for (int d = 0; d < 3; ++d) centroid[d][i] = c[d];
  j[0][i] = jm(0, 0);
  j[1][i] = jm(1, 1);
  j[2][i] = jm(2, 2);
  j[3][i] = jm(0, 1);
  j[4][i] = jm(0, 2);
  j[5][i] = jm(1, 2);
}

ElasticCondensation ElasticCondensation::build(const ContactNetwork& net,
                                               const std::vector<Vec3>& x0) {
  ElasticCondensation e;
  const auto nc = static_cast<std::size_t>(net.contact_count());
  CondensedSums& k = e.sums;
  k.resize(nc);
  e.eligible.assign(nc, 0);
  for (Index c = 0; c < net.contact_count(); ++c) {
    const auto i = static_cast<std::size_t>(c);
    const Index begin = net.point_begin[c], end = net.point_begin[c + 1];
    const Vec3& xa0 = x0[net.particle_a[c]];
    const Vec3 offset0 = x0[net.particle_b[c]] - xa0;  // as the point loop forms it
    for (int d = 0; d < 3; ++d) k.offset0[d][i] = offset0[d];  // the frames read it too
    if (end == begin) continue;
    const Real alpha = net.constants[begin].ks / net.constants[begin].kn;
    bool uniform = true;
    Real u_n0 = std::numeric_limits<Real>::infinity(), u_s0 = u_n0;
    for (Index m = begin; m < end; ++m) {
      const LocalPointConstants& p = net.constants[m];
      uniform &= std::abs(p.ks - alpha * p.kn) <= 1e-12 * p.ks;
      u_n0 = std::min(u_n0, p.fn_max / p.kn);
      u_s0 = std::min(u_s0, p.c_max / p.ks);
    }
    store_point_sums(
        k, i, begin, end, xa0, [&](Index m) { return net.constants[m].kn; },
        [&](Index m) { return net.point_position0[m]; }, [](Index) { return true; });
    k.alpha[i] = alpha;
    k.u_n0[i] = u_n0;
    k.u_s0[i] = u_s0;
    // A zero or NaN limit (zero strength) never passes the bound; nothing else to exclude.
    e.eligible[i] = uniform && k.k_n[i] > 0 && std::isfinite(alpha);
  }
  e.intact = e.eligible;
  e.condensed.assign(nc, 0);
  e.held.resize(net.contact_count());
  return e;
}

void ElasticCondensation::reset_flags(const ContactNetwork& net, const PointDamage& damage) {
  for (Index c = 0; c < net.contact_count(); ++c) {
    bool all_intact = eligible[static_cast<std::size_t>(c)] != 0;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m)
      all_intact &= damage[static_cast<std::size_t>(m)] == 0;
    intact[static_cast<std::size_t>(c)] = all_intact;
  }
  std::fill(condensed.begin(), condensed.end(), std::uint8_t{0});
  held.clear();
  any_condensed = false;
}

namespace {

// A condensed contact's elastic energy (elastic_condensation.hpp) from the kernel's terms: K, alpha,
// u_cn, u_c, n, D and J D^T (column-major, jd[i + 3 j] = (J D^T)_ij), with
//   tr(D J D^T) = sum_ik D_ik (J D^T)_ki,  n^T D J D^T n = n . (D (J D^T n)).
// Plain scalars in one fixed order, which the kernel writes out in its loop (called there, it kept
// GCC from vectorising): the lanes and condensed_strain_energy give the same bits (tested).
[[gnu::always_inline]] inline Real energy_from_terms(Real k, Real al, Real ucn, const Real* uc,
                                                     const Real* n, const Real* d,
                                                     const Real* jd) {
  const Real v0 = jd[0] * n[0] + jd[3] * n[1] + jd[6] * n[2];  // J D^T n
  const Real v1 = jd[1] * n[0] + jd[4] * n[1] + jd[7] * n[2];
  const Real v2 = jd[2] * n[0] + jd[5] * n[1] + jd[8] * n[2];
  const Real q = n[0] * (d[0] * v0 + d[3] * v1 + d[6] * v2) +
                 n[1] * (d[1] * v0 + d[4] * v1 + d[7] * v2) +
                 n[2] * (d[2] * v0 + d[5] * v1 + d[8] * v2);
  const Real tr = (d[0] * jd[0] + d[3] * jd[1] + d[6] * jd[2]) +
                  (d[1] * jd[3] + d[4] * jd[4] + d[7] * jd[5]) +
                  (d[2] * jd[6] + d[5] * jd[7] + d[8] * jd[8]);
  const Real uc_sq = uc[0] * uc[0] + uc[1] * uc[1] + uc[2] * uc[2];
  return 0.5 * ((1 - al) * (k * ucn * ucn + q) + al * (k * uc_sq + tr));
}

// J D^T, column-major (jd[i + 3 j] = (J D^T)_ij), from J's six entries (xx, yy, zz, xy, xz, yz).
[[gnu::always_inline]] inline void j_times_dt(const Real* jm, const Real* d, Real* jd) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      jd[i + 3 * j] = jm[i] * d[j] + jm[i + 3] * d[j + 3] + jm[i + 6] * d[j + 6];
}

// kEnergy: each contact's elastic energy is stored too (in.energy), for a step whose state a
// history row reports.
template <bool kEnergy>
[[gnu::always_inline]] inline void condensed_block_lanes(const CondensedInputs& in, Index begin,
                                                         Index count, ContactState& cs,
                                                         CondensedBlock& out) {
  // Poses: 8 doubles per body (state/body_poses.hpp), x then the quaternion (w, x, y, z).
  const Real* pose = in.pose;
  const auto at = [begin](const std::vector<Real>& v) { return v.data() + begin; };
  const Real *k_n = at(in.sums.k_n), *alpha = at(in.sums.alpha), *radius = at(in.sums.radius);
  const Real *u_n0 = at(in.sums.u_n0), *u_s0 = at(in.sums.u_s0);
  const Real *cx = at(in.sums.centroid[0]), *cy = at(in.sums.centroid[1]),
             *cz = at(in.sums.centroid[2]);
  const Real *r0x = at(in.sums.offset0[0]), *r0y = at(in.sums.offset0[1]),
             *r0z = at(in.sums.offset0[2]);
  const Real *jxx = at(in.sums.j[0]), *jyy = at(in.sums.j[1]), *jzz = at(in.sums.j[2]),
             *jxy = at(in.sums.j[3]), *jxz = at(in.sums.j[4]), *jyz = at(in.sums.j[5]);
  Real* force_b = cs.force_b[begin].data();
  Real* torque_b = cs.torque_b[begin].data();
  Real* torque_a = cs.torque_a[begin].data();
  Real* energy = kEnergy ? in.energy + begin : nullptr;
  const Index* pa = in.particle_a + begin;
  const Index* pb = in.particle_b + begin;
  constexpr Real kMargin = 1.0 - 1e-3;
  // B's poses are scattered over the bodies (contacts are sorted by A): their misses were a fifth
  // of the kernel, taken one vector iteration at a time. Requested all at once here, they overlap.
  for (Index l = count; l < std::min(2 * count, in.contact_count - begin); ++l)
    __builtin_prefetch(pose + BodyPoses::kStride * pb[l]);
#pragma omp simd
  for (Index l = 0; l < count; ++l) {
    const Index a = pa[l], b = pb[l];
    // Indexed from the array's base (a per-lane pointer defeats GCC's gathers).
    const Index ia = BodyPoses::kStride * a, ib = BodyPoses::kStride * b;
    // dx = x_B - x_A and the unit normal n along it.
    Real dx[3], n[3];
    for (int i = 0; i < 3; ++i) dx[i] = pose[ib + i] - pose[ia + i];
    // One division, not three (the divisions were an eighth of the kernel).
    const Real inv_len = 1.0 / std::sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    for (int i = 0; i < 3; ++i) n[i] = dx[i] * inv_len;
    Real ra[9], rb[9];
    rotation_from_quaternion(pose[ia + 3], pose[ia + 4], pose[ia + 5], pose[ia + 6], ra);
    rotation_from_quaternion(pose[ib + 3], pose[ib + 4], pose[ib + 5], pose[ib + 6], rb);
    // D = R_B - R_A, S = (R_A + R_B) / 2; u0 = dx - R_B r0 (SPEC 4).
    Real d[9], sm[9];
    Real d_sq = 0;
    for (int e = 0; e < 9; ++e) {
      d[e] = rb[e] - ra[e];
      sm[e] = 0.5 * (ra[e] + rb[e]);
      d_sq += d[e] * d[e];
    }
    const Real rc[3] = {cx[l], cy[l], cz[l]};
    Real u0[3], uc[3], ac[3];
    for (int i = 0; i < 3; ++i) {
      u0[i] = offset_displacement(dx[i], rb[i], rb[i + 3], rb[i + 6], r0x[l], r0y[l], r0z[l]);
      uc[i] = u0[i] + d[i] * rc[0] + d[i + 3] * rc[1] + d[i + 6] * rc[2];
      ac[i] = 0.5 * u0[i] + sm[i] * rc[0] + sm[i + 3] * rc[1] + sm[i + 6] * rc[2];
    }
    const Real ucn = n[0] * uc[0] + n[1] * uc[1] + n[2] * uc[2];
    // The bound (see above), squared: e = |D|_2 radius, with |D|_2^2 = |D|_F^2 / 2 exactly for a
    // difference of two rotations (D = R_A (Q - I), Q = R_A^T R_B turning by phi: singular values
    // 2 sin(phi / 2), twice, and 0), half the Frobenius bound's square.
    const Real spread_sq = 0.5 * d_sq * (radius[l] * radius[l]);
    const Real room_n = kMargin * u_n0[l] - ucn;
    Real us_sq = 0;
    for (int i = 0; i < 3; ++i) {
      const Real us = uc[i] - ucn * n[i];
      us_sq += us * us;
    }
    const Real limit_s = kMargin * u_s0[l];
    // Bitwise: no branch in the lanes (the caller adds `intact`: bytes in lanes of doubles).
    out.below_limits[l] = (room_n > 0) & (spread_sq < room_n * room_n) &
                          (2 * (us_sq + spread_sq) < limit_s * limit_s);
    // F = -K (alpha u_c + (1 - alpha) u_cn n).
    Real f[3];
    const Real al = alpha[l];
    for (int i = 0; i < 3; ++i) f[i] = -k_n[l] * (al * uc[i] + (1 - al) * ucn * n[i]);
    // P = S J D^T, J symmetric (xx, yy, zz, xy, xz, yz).
    const Real jm[9] = {jxx[l], jxy[l], jxz[l], jxy[l], jyy[l], jyz[l], jxz[l], jyz[l], jzz[l]};
    Real jd[9];  // J D^T, column-major (as j_times_dt)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        jd[i + 3 * j] = jm[i] * d[j] + jm[i + 3] * d[j + 3] + jm[i + 6] * d[j + 6];
    if constexpr (kEnergy) {
      // energy_from_terms, written out (see there).
      const Real v0 = jd[0] * n[0] + jd[3] * n[1] + jd[6] * n[2];
      const Real v1 = jd[1] * n[0] + jd[4] * n[1] + jd[7] * n[2];
      const Real v2 = jd[2] * n[0] + jd[5] * n[1] + jd[8] * n[2];
      const Real q = n[0] * (d[0] * v0 + d[3] * v1 + d[6] * v2) +
                     n[1] * (d[1] * v0 + d[4] * v1 + d[7] * v2) +
                     n[2] * (d[2] * v0 + d[5] * v1 + d[8] * v2);
      const Real tr = (d[0] * jd[0] + d[3] * jd[1] + d[6] * jd[2]) +
                      (d[1] * jd[3] + d[4] * jd[4] + d[7] * jd[5]) +
                      (d[2] * jd[6] + d[5] * jd[7] + d[8] * jd[8]);
      const Real uc_sq = uc[0] * uc[0] + uc[1] * uc[1] + uc[2] * uc[2];
      const Real kn = k_n[l];
      energy[l] = 0.5 * ((1 - al) * (kn * ucn * ucn + q) + al * (kn * uc_sq + tr));
    }
    Real p[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        p[i + 3 * j] = sm[i] * jd[3 * j] + sm[i + 3] * jd[1 + 3 * j] + sm[i + 6] * jd[2 + 3 * j];
    const Real axial[3] = {p[1 + 6] - p[2 + 3], p[2] - p[6], p[3] - p[1]};
    Real pn[3];
    for (int i = 0; i < 3; ++i) pn[i] = p[i] * n[0] + p[i + 3] * n[1] + p[i + 6] * n[2];
    // M_A = a_c x F - alpha axial(P) - (1 - alpha) (P n) x n.
    const Real mom[3] = {
        ac[1] * f[2] - ac[2] * f[1] - al * axial[0] - (1 - al) * (pn[1] * n[2] - pn[2] * n[1]),
        ac[2] * f[0] - ac[0] * f[2] - al * axial[1] - (1 - al) * (pn[2] * n[0] - pn[0] * n[2]),
        ac[0] * f[1] - ac[1] * f[0] - al * axial[2] - (1 - al) * (pn[0] * n[1] - pn[1] * n[0])};
    const Real dxf[3] = {dx[1] * f[2] - dx[2] * f[1], dx[2] * f[0] - dx[0] * f[2],
                         dx[0] * f[1] - dx[1] * f[0]};
    for (int i = 0; i < 3; ++i) {
      force_b[3 * l + i] = f[i];
      torque_b[3 * l + i] = mom[i] - dxf[i];
      torque_a[3 * l + i] = -mom[i];
    }
  }
}

void condensed_block_lanes_baseline(const CondensedInputs& in, Index begin, Index count,
                                    ContactState& cs, CondensedBlock& out) {
  if (in.energy) return condensed_block_lanes<true>(in, begin, count, cs, out);
  condensed_block_lanes<false>(in, begin, count, cs, out);
}
#if RCDEM_SIMD_MULTIVERSION
RCDEM_SIMD_TARGET_AVX2 void condensed_block_lanes_avx2(const CondensedInputs& in, Index begin,
                                                       Index count, ContactState& cs,
                                                       CondensedBlock& out) {
  if (in.energy) return condensed_block_lanes<true>(in, begin, count, cs, out);
  condensed_block_lanes<false>(in, begin, count, cs, out);
}
RCDEM_SIMD_TARGET_AVX512 void condensed_block_lanes_avx512(const CondensedInputs& in, Index begin,
                                                           Index count, ContactState& cs,
                                                           CondensedBlock& out) {
  if (in.energy) return condensed_block_lanes<true>(in, begin, count, cs, out);
  condensed_block_lanes<false>(in, begin, count, cs, out);
}
#endif

}  // namespace

void evaluate_condensed_block(const CondensedInputs& in, Index begin, Index count, ContactState& cs,
                              CondensedBlock& out) {
#if RCDEM_SIMD_MULTIVERSION
  switch (simd_level()) {
    case SimdLevel::Avx512:
      return condensed_block_lanes_avx512(in, begin, count, cs, out);
    case SimdLevel::Avx2:
      return condensed_block_lanes_avx2(in, begin, count, cs, out);
    case SimdLevel::Baseline:
      break;
  }
#endif
  condensed_block_lanes_baseline(in, begin, count, cs, out);
}

Real condensed_strain_energy(const CondensedSums& s, Index c, const Real* pose, Index a,
                             Index b) {
  // The kernel's terms in the kernel's order (condensed_block_lanes above): the same bits.
  const auto i = static_cast<std::size_t>(c);
  const Index ia = BodyPoses::kStride * a, ib = BodyPoses::kStride * b;
  Real dx[3], n[3];
  for (int k = 0; k < 3; ++k) dx[k] = pose[ib + k] - pose[ia + k];
  const Real inv_len = 1.0 / std::sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
  for (int k = 0; k < 3; ++k) n[k] = dx[k] * inv_len;
  Real ra[9], rb[9], d[9];
  rotation_from_quaternion(pose[ia + 3], pose[ia + 4], pose[ia + 5], pose[ia + 6], ra);
  rotation_from_quaternion(pose[ib + 3], pose[ib + 4], pose[ib + 5], pose[ib + 6], rb);
  for (int e = 0; e < 9; ++e) d[e] = rb[e] - ra[e];
  const Real rc[3] = {s.centroid[0][i], s.centroid[1][i], s.centroid[2][i]};
  Real uc[3];
  for (int k = 0; k < 3; ++k) {
    const Real u0 = offset_displacement(dx[k], rb[k], rb[k + 3], rb[k + 6], s.offset0[0][i],
                                        s.offset0[1][i], s.offset0[2][i]);
    uc[k] = u0 + d[k] * rc[0] + d[k + 3] * rc[1] + d[k + 6] * rc[2];
  }
  const Real ucn = n[0] * uc[0] + n[1] * uc[1] + n[2] * uc[2];
  const Real jm[9] = {s.j[0][i], s.j[3][i], s.j[4][i], s.j[3][i], s.j[1][i],
                      s.j[5][i], s.j[4][i], s.j[5][i], s.j[2][i]};
  Real jd[9];
  j_times_dt(jm, d, jd);
  return energy_from_terms(s.k_n[i], s.alpha[i], ucn, uc, n, d, jd);
}

Index ElasticCondensation::condensed_count() const {
  return static_cast<Index>(std::count(condensed.begin(), condensed.end(), std::uint8_t{1}));
}

namespace {

// The local points of the contacts whose flag is set.
Index flagged_points(const std::vector<std::uint8_t>& flag, const ContactNetwork& net) {
  Index n = 0;
  for (Index c = 0; c < static_cast<Index>(flag.size()); ++c)
    if (flag[static_cast<std::size_t>(c)]) n += net.points_of(c);
  return n;
}

}  // namespace

Index ElasticCondensation::condensed_point_count(const ContactNetwork& net) const {
  return flagged_points(condensed, net);
}

Index ElasticCondensation::held_point_count(const ContactNetwork& net) const {
  return flagged_points(held.held, net);
}

}  // namespace rcdem
