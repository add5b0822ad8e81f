#include "rcdem/contact/held_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "rcdem/contact/contact_kinematics.hpp"
#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/contact/laws/bilinear_softening.hpp"
#include "rcdem/core/simd_level.hpp"
#include "rcdem/core/small_angle.hpp"
#include "rcdem/state/body_poses.hpp"

namespace rcdem {

static_assert(HeldContacts::kBlock == CondensedBlock::kSize,
              "held sums are kept per block of the loop");

void HeldContacts::resize(Index contacts) {
  held.assign(static_cast<std::size_t>(contacts), 0);
  saved.assign(static_cast<std::size_t>(contacts), 0);
  softening_clock.assign(static_cast<std::size_t>(contacts), 0);
  block.assign(static_cast<std::size_t>((contacts + kBlock - 1) / kBlock), {});
}

HeldSums& HeldContacts::sums(Index c) {
  std::vector<HeldSums>& b = block[static_cast<std::size_t>(c / kBlock)];
  if (b.empty()) b.resize(kBlock);
  return b[static_cast<std::size_t>(c % kBlock)];
}

const HeldSums& HeldContacts::sums(Index c) const {
  return block[static_cast<std::size_t>(c / kBlock)][static_cast<std::size_t>(c % kBlock)];
}

Index HeldContacts::count() const {
  return static_cast<Index>(std::count(held.begin(), held.end(), std::uint8_t{1}));
}

void HeldContacts::clear() {
  std::fill(held.begin(), held.end(), std::uint8_t{0});
  std::fill(saved.begin(), saved.end(), std::uint8_t{0});
  std::fill(softening_clock.begin(), softening_clock.end(), std::int16_t{0});
  entry.clear();
  current = false;
}

void HeldContacts::keep_entries(const Index* point_begin, LocalPointRecord* points) {
  std::erase_if(entry, [this](const auto& e) { return !saved[static_cast<std::size_t>(e.first)]; });
  for (std::size_t c = 0; c < held.size(); ++c) {
    if (!held[c]) continue;
    const auto ci = static_cast<Index>(c);
    LocalPointRecord* first = points + point_begin[ci];
    const Index count = point_begin[ci + 1] - point_begin[ci];
    if (saved[c]) {
      const std::vector<PlanePointState>& e = entry.at(ci);
      for (Index m = 0; m < count; ++m) first[m].history = e[static_cast<std::size_t>(m)];
      continue;
    }
    std::vector<PlanePointState>& e = entry[ci];
    e.resize(static_cast<std::size_t>(count));
    for (Index m = 0; m < count; ++m) e[static_cast<std::size_t>(m)] = first[m].history;
    saved[c] = 1;
  }
}

void HeldContacts::take_entry(Index c, LocalPointRecord* points, Index count) {
  const auto i = static_cast<std::size_t>(c);
  if (!saved[i]) return;
  saved[i] = 0;
  if (!points) return;
  const std::vector<PlanePointState>& e = entry.find(c)->second;
  for (Index m = 0; m < count; ++m) points[m].history = e[static_cast<std::size_t>(m)];
}

namespace {

// The elastic limits are approached no closer than the intact condensation's margin; every room
// also gives up a part in 1e9 of the displacements it is a difference of, so that rounding in the
// bound never lets a point cross what the law compares.
constexpr Real kLimitMargin = 1.0 - 1e-3;
constexpr Real kRounding = 1e-9;

// A point's room along n and across it (held_contacts.hpp).
void point_rooms(const LocalPointRecord& p, Real& room_n, Real& room_s) {
  const PlanePointState& s = p.history;
  const LocalPointConstants& k = p.constants;
  const Real un_limit = std::max(s.un_max, kLimitMargin * k.fn_max / k.kn);
  const Real to_cap_n = ((1 - s.damage) * k.fn_max - s.fn) / k.kn;
  room_n = std::min(to_cap_n, un_limit - s.un) - kRounding * (std::abs(un_limit) + std::abs(s.un));
  const Real us = std::sqrt(s.us.squaredNorm());
  const Real us_limit = std::max(std::sqrt(s.us_max_sq), kLimitMargin * k.c_max / k.ks);
  const Real to_cap_s = ((1 - s.damage) * k.c_max - std::sqrt(s.fs.squaredNorm())) / k.ks;
  room_s = std::min(to_cap_s, us_limit - us) - kRounding * (us_limit + us);
}

// The frame's third axis and what the points of a held contact read of the kinematics, from the
// axes n, t1, the orientations ra, rb (column-major) and dx = x_B - x_A, r0 = x_B0 - x_A0: the
// products of contact_loop.hpp's frame_kinematics on plain scalars (rows of disp and arm: r).
// Arrays by reference, not pointer: a local array whose address is taken in a SIMD loop becomes a
// per-lane array in memory that GCC cannot store to.
[[gnu::always_inline]] inline void held_kinematics(const Real (&n)[3], const Real (&t1)[3],
                                                   const Real (&ra)[9], const Real (&rb)[9],
                                                   const Real (&dx)[3], const Real (&r0)[3],
                                                   Real (&disp0)[3], Real (&disp)[9],
                                                   Real (&arm)[9]) {
  // E^T, row-major: rows n, t1, t2 = n x t1.
  const Real e[9] = {n[0],
                     n[1],
                     n[2],
                     t1[0],
                     t1[1],
                     t1[2],
                     n[1] * t1[2] - n[2] * t1[1],
                     n[2] * t1[0] - n[0] * t1[2],
                     n[0] * t1[1] - n[1] * t1[0]};
  Real u0[3];
  for (int i = 0; i < 3; ++i)
    u0[i] = offset_displacement(dx[i], rb[i], rb[i + 3], rb[i + 6], r0[0], r0[1], r0[2]);
  for (int r = 0; r < 3; ++r) {
    disp0[r] = e[3 * r] * u0[0] + e[3 * r + 1] * u0[1] + e[3 * r + 2] * u0[2];
    for (int k = 0; k < 3; ++k) {
      disp[3 * r + k] = e[3 * r] * (rb[3 * k] - ra[3 * k]) +
                        e[3 * r + 1] * (rb[3 * k + 1] - ra[3 * k + 1]) +
                        e[3 * r + 2] * (rb[3 * k + 2] - ra[3 * k + 2]);
      arm[3 * r + k] = e[3 * r] * (0.5 * (ra[3 * k] + rb[3 * k])) +
                       e[3 * r + 1] * (0.5 * (ra[3 * k + 1] + rb[3 * k + 1])) +
                       e[3 * r + 2] * (0.5 * (ra[3 * k + 2] + rb[3 * k + 2]));
    }
  }
}

// held_kinematics at the poses of bodies a and b (BodyPoses), in the frame (n, t1), for contact i
// of the sums (its x_B0 - x_A0): what the entry and the energy after a step read, with the
// kernel's arithmetic.
void kinematics_at_poses(const CondensedSums& s, std::size_t i, const Vec3& n, const Vec3& t1,
                         const Real* pose, Index a, Index b, Real (&disp0)[3], Real (&disp)[9]) {
  const Index ia = BodyPoses::kStride * a, ib = BodyPoses::kStride * b;
  Real dx[3], ra[9], rb[9], arm[9];
  for (int k = 0; k < 3; ++k) dx[k] = pose[ib + k] - pose[ia + k];
  rotation_from_quaternion(pose[ia + 3], pose[ia + 4], pose[ia + 5], pose[ia + 6], ra);
  rotation_from_quaternion(pose[ib + 3], pose[ib + 4], pose[ib + 5], pose[ib + 6], rb);
  const Real nn[3] = {n.x(), n.y(), n.z()}, tt[3] = {t1.x(), t1.y(), t1.z()};
  const Real r0[3] = {s.offset0[0][i], s.offset0[1][i], s.offset0[2][i]};
  held_kinematics(nn, tt, ra, rb, dx, r0, disp0, disp, arm);
}

// The sums' numbers in HeldSums order (phi0, q, energy0, room_n, room_s, disp0, disp,
// open_margin, last_du_n, last_dd_n, slope_n, shrink_s).
constexpr int kHeldSize = 34;
static_assert(sizeof(HeldSums) == kHeldSize * sizeof(Real), "HeldSums is 34 doubles");

// du_c = d0 + dD r_c and dD (row-major) since the entry, from the sums `h` (HeldSums order).
template <typename H>
[[gnu::always_inline]] inline void change_since_entry(const H& h, const Real (&rc)[3],
                                                      const Real (&disp0)[3], const Real (&disp)[9],
                                                      Real (&du)[3], Real (&dd)[9]) {
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) dd[3 * r + k] = disp[3 * r + k] - h[18 + 3 * r + k];
    du[r] = (disp0[r] - h[15 + r]) +
            (dd[3 * r] * rc[0] + dd[3 * r + 1] * rc[1] + dd[3 * r + 2] * rc[2]);
  }
}

// Whether every point of a held contact stays in its room, from the change since entry du (at the
// centroid), dD (row-major) and the radius, with the sums h (HeldSums order).
template <typename H>
[[gnu::always_inline]] inline bool inside_rooms(const H& h, const Real (&du)[3],
                                                const Real (&dd)[9], Real radius) {
  // The spread of the points about the centroid, row by row: along n |dD row n| |rho|max, across
  // it the Frobenius norm of the t1, t2 rows (at least their spectral norm) times |rho|max.
  Real dd_n_sq = 0.0, dd_s_sq = 0.0;
  for (int e = 0; e < 3; ++e) dd_n_sq += dd[e] * dd[e];
  for (int e = 3; e < 9; ++e) dd_s_sq += dd[e] * dd[e];
  const Real spread_n = std::sqrt(dd_n_sq) * radius;
  const Real spread_s = std::sqrt(dd_s_sq) * radius;
  const Real du_s = std::sqrt(du[1] * du[1] + du[2] * du[2]);
  // Broken points keep opening, step by step: the change of du_n at any point since the last
  // step, at least that of du_cn less |change of dD's row n| |rho|max, is not below the margin.
  Real step_dd_sq = 0.0;
  for (int e = 0; e < 3; ++e) step_dd_sq += (dd[e] - h[29 + e]) * (dd[e] - h[29 + e]);
  const bool opening = (h[27] < 0) | ((du[0] - h[28]) - std::sqrt(step_dd_sq) * radius >= h[27]);
  // Softening points' shear caps shrink as they open: by shrink_s per unit of their opening.
  const Real room_s = h[14] - h[33] * std::max(du[0] + spread_n, 0.0);
  return (du[0] + spread_n < h[13]) & (du_s + spread_s < room_s) & opening;
}

// The energy (held_contacts.hpp) from the change, K, alpha and J (row-major). Along n the
// points' slope is slope_n kn and their energy fn^2 / 2 kn, so that row's work carries slope_n
// and its quadratic term slope_n^2 (both 1 inside the envelope).
template <typename H>
[[gnu::always_inline]] inline Real energy_from_change(const H& h, Real k, Real al,
                                                      const Real (&jm)[9], const Real (&du)[3],
                                                      const Real (&dd)[9]) {
  const Real slope = h[32];
  const Real l[3] = {slope * slope, al, al};
  Real work = 0.0, quad = 0.0;
  for (int r = 0; r < 3; ++r) {
    work += h[r] * du[r];
    quad += k * l[r] * du[r] * du[r];
    Real djd = 0.0;  // (dD J dD^T)_rr
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) djd += dd[3 * r + a] * jm[3 * a + b] * dd[3 * r + b];
    quad += l[r] * djd;
    for (int m = 0; m < 3; ++m) work += dd[3 * r + m] * h[3 + 3 * m + r];  // dD_rm Q_mr
    if (r == 0) work *= slope;
  }
  return h[12] - work + 0.5 * quad;
}

// The energy softening points dissipate in the step (BilinearSoftening::update: the mean force
// times (fn_trial - fn) / kn, (1 + beta) du_n at each point, slope_n = -beta), from the change
// since entry du, dD and the last step's (h), K and J: with fn_J = fn_J(t0) - beta kn_J du_Jn,
//   sum_J (fn_J(t - 1) + fn_J(t)) / 2 (1 + beta) delta_J,  delta_J = du_Jn(t) - du_Jn(t - 1),
// summed through Phi0, Q's column n, K and J as the force is. Zero for points inside the envelope.
template <typename H>
[[gnu::always_inline]] inline Real softening_dissipation(const H& h, Real k, const Real (&jm)[9],
                                                         const Real (&du)[3], const Real (&dd)[9]) {
  const Real beta = -h[32];
  const Real step_c = du[0] - h[28], sum_c = du[0] + h[28];
  Real force_step = h[0] * step_c, quad = k * sum_c * step_c;  // -sum fn0 delta; sum kn s delta
  for (int a = 0; a < 3; ++a) {
    const Real step_a = dd[a] - h[29 + a];
    force_step += h[3 + 3 * a] * step_a;
    for (int b = 0; b < 3; ++b) quad += (dd[b] + h[29 + b]) * jm[3 * b + a] * step_a;
  }
  const Real d = 0.5 * (1 + beta) * (-2 * force_step - beta * quad);
  return beta > 0 ? d : 0.0;
}

// A block's held contacts `list[0, count)` (kHeld: with their energies), in SIMD lanes: the turned
// frame (SPEC 4, PlaneRotation's arithmetic), the kinematics, the bound and the sums' force and
// moment. A lane whose turn leaves the common case (normal turned past 120 degrees, spin of
// 0.1 rad or more, degenerate axis) is not kept: the caller releases it to the point loop, whose
// scalar frame handles those.
// Each array a little longer than a block: at 1 KB apart, every fourth array of a lane's column
// shares its address modulo 4 KB, and the stores that fill a column stalled on it (4K aliasing).
constexpr Index kLanes = HeldContacts::kBlock + 9;
struct HeldLanes {
  Real no[3][kLanes], to[3][kLanes], wsum[3][kLanes], r0[3][kLanes], rc[3][kLanes], j[6][kLanes];
  Real h[kHeldSize][kLanes];
  Real kn[kLanes], al[kLanes], radius[kLanes];
  Real pa[7][kLanes], pb[7][kLanes];  // A's and B's poses: x, then the quaternion (w, x, y, z)
};

// Lane l's HeldSums, read in place (a copy into a local array kept GCC from vectorising).
struct LaneSums {
  const HeldLanes& g;
  Index l;
  [[gnu::always_inline]] Real operator[](int k) const { return g.h[k][l]; }
};

// Every lane's numbers, gathered into arrays indexed by the lane before the lanes run: loads
// through a gathered contact number, and 64-bit products by 3 or 27 (no SIMD instruction below
// AVX-512DQ), kept GCC from vectorising the lanes' loop.
[[gnu::always_inline]] inline void gather_lanes(const HeldInputs& in, const Index* list,
                                                Index count, HeldLanes& g) {
  const CondensedSums& s = in.sums;
  // First what lies outside the block's data (the spins, the stored frames), then the sums, each
  // in a short loop per contact of its own, so that the core has many contacts' misses in flight
  // at once (in one long loop it waited on each contact's lines in turn).
  for (Index l = 0; l < count; ++l) {
    const Index c = list[l], a = in.particle_a[c], b = in.particle_b[c];
    for (int k = 0; k < 3; ++k) {
      g.no[k][l] = in.normal[3 * c + k];
      g.to[k][l] = in.tangent[3 * c + k];
      g.wsum[k][l] = in.w[3 * a + k] + in.w[3 * b + k];
    }
  }
  for (Index l = 0; l < count; ++l) {
    const Real* h = in.held_sums + kHeldSize * (list[l] - in.begin);
    for (int k = 0; k < kHeldSize; ++k) g.h[k][l] = h[k];
  }
  for (Index l = 0; l < count; ++l) {
    const Index c = list[l], a = in.particle_a[c], b = in.particle_b[c];
    const auto i = static_cast<std::size_t>(c);
    for (int k = 0; k < 3; ++k) {
      g.r0[k][l] = s.offset0[k][i];
      g.rc[k][l] = s.centroid[k][i];
    }
    for (int k = 0; k < 6; ++k) g.j[k][l] = s.j[k][i];
    g.kn[l] = s.k_n[i];
    g.al[l] = s.alpha[i];
    g.radius[l] = s.radius[i];
    for (int k = 0; k < 7; ++k) {
      g.pa[k][l] = in.pose[BodyPoses::kStride * a + k];
      g.pb[k][l] = in.pose[BodyPoses::kStride * b + k];
    }
  }
}

template <bool kEnergy>
[[gnu::always_inline]] inline void held_block_lanes(const HeldInputs& in, const Index* list,
                                                    Index count, HeldLanes& g, HeldOutputs& out) {
  gather_lanes(in, list, count, g);
  const Real dt = in.dt;
#pragma omp simd
  for (Index l = 0; l < count; ++l) {
    const LaneSums hl{g, l};
    Real dx[3], n[3], no[3], to[3];
    for (int i = 0; i < 3; ++i) {
      dx[i] = g.pb[i][l] - g.pa[i][l];
      no[i] = g.no[i][l];
      to[i] = g.to[i][l];
    }
    const Real inv_len = 1.0 / std::sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    for (int i = 0; i < 3; ++i) n[i] = dx[i] * inv_len;
    // R v = c v + k x v + k (k.v) / (1 + c), k = n_old x n, c = n_old . n.
    const Real kk[3] = {no[1] * n[2] - no[2] * n[1], no[2] * n[0] - no[0] * n[2],
                        no[0] * n[1] - no[1] * n[0]};
    const Real cc = no[0] * n[0] + no[1] * n[1] + no[2] * n[2];
    const Real kt = (kk[0] * to[0] + kk[1] * to[1] + kk[2] * to[2]) / (1.0 + cc);
    Real r[3] = {cc * to[0] + (kk[1] * to[2] - kk[2] * to[1]) + kt * kk[0],
                 cc * to[1] + (kk[2] * to[0] - kk[0] * to[2]) + kt * kk[1],
                 cc * to[2] + (kk[0] * to[1] - kk[1] * to[0]) + kt * kk[2]};
    // About n by the pair's spin: cos(spin) r + sin(spin) n x r.
    const Real spin = 0.5 * dt * (g.wsum[0][l] * n[0] + g.wsum[1][l] * n[1] + g.wsum[2][l] * n[2]);
    Real cos_spin, sinc;
    small_angle_cos_sinc(spin * spin, cos_spin, sinc);
    const Real sin_spin = spin * sinc;
    const Real nr[3] = {n[1] * r[2] - n[2] * r[1], n[2] * r[0] - n[0] * r[2],
                        n[0] * r[1] - n[1] * r[0]};
    for (int i = 0; i < 3; ++i) r[i] = cos_spin * r[i] + sin_spin * nr[i];
    const Real rn = r[0] * n[0] + r[1] * n[1] + r[2] * n[2];
    for (int i = 0; i < 3; ++i) r[i] -= rn * n[i];
    const Real r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    const Real inv_r = 1.0 / std::sqrt(r2);
    const Real t1[3] = {r[0] * inv_r, r[1] * inv_r, r[2] * inv_r};
    Real ra[9], rb[9], disp0[3], disp[9], arm[9];
    rotation_from_quaternion(g.pa[3][l], g.pa[4][l], g.pa[5][l], g.pa[6][l], ra);
    rotation_from_quaternion(g.pb[3][l], g.pb[4][l], g.pb[5][l], g.pb[6][l], rb);
    const Real r0[3] = {g.r0[0][l], g.r0[1][l], g.r0[2][l]};
    held_kinematics(n, t1, ra, rb, dx, r0, disp0, disp, arm);
    const Real rc[3] = {g.rc[0][l], g.rc[1][l], g.rc[2][l]};
    Real du[3], dd[9];
    change_since_entry(hl, rc, disp0, disp, du, dd);
    const bool inside = inside_rooms(hl, du, dd, g.radius[l]);
    out.kept[l] = (cc > -0.5) & is_small_angle(spin * spin) & (r2 > 0.25) & inside;
    out.du_n[l] = du[0];
    for (int e = 0; e < 3; ++e) out.dd_n[e][l] = dd[e];
    // Force and moment in the frame (held_contacts.hpp), then in the world.
    const Real kn = g.kn[l], al = g.al[l];
    const Real lam[3] = {hl[32], al, al};
    // J's six entries are xx, yy, zz, xy, xz, yz.
    const Real jm[9] = {g.j[0][l], g.j[3][l], g.j[4][l], g.j[3][l], g.j[1][l],
                        g.j[5][l], g.j[4][l], g.j[5][l], g.j[2][l]};
    Real phi[3], ac[3];
    for (int i = 0; i < 3; ++i) {
      phi[i] = hl[i] - kn * lam[i] * du[i];
      ac[i] =
          0.5 * disp0[i] + (arm[3 * i] * rc[0] + arm[3 * i + 1] * rc[1] + arm[3 * i + 2] * rc[2]);
    }
    Real aj[9], aq[9], p[9];  // arm J, arm Q, arm J dD^T L (row-major)
    for (int i = 0; i < 3; ++i)
      for (int m = 0; m < 3; ++m) {
        aj[3 * i + m] =
            arm[3 * i] * jm[m] + arm[3 * i + 1] * jm[3 + m] + arm[3 * i + 2] * jm[6 + m];
        aq[3 * i + m] =
            arm[3 * i] * hl[3 + m] + arm[3 * i + 1] * hl[6 + m] + arm[3 * i + 2] * hl[9 + m];
      }
    for (int i = 0; i < 3; ++i)
      for (int m = 0; m < 3; ++m)
        p[3 * i + m] = lam[m] * (aj[3 * i] * dd[3 * m] + aj[3 * i + 1] * dd[3 * m + 1] +
                                 aj[3 * i + 2] * dd[3 * m + 2]);
    const Real mom[3] = {ac[1] * phi[2] - ac[2] * phi[1] + (aq[5] - aq[7]) - (p[5] - p[7]),
                         ac[2] * phi[0] - ac[0] * phi[2] + (aq[6] - aq[2]) - (p[6] - p[2]),
                         ac[0] * phi[1] - ac[1] * phi[0] + (aq[1] - aq[3]) - (p[1] - p[3])};
    const Real t2[3] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                        n[0] * t1[1] - n[1] * t1[0]};
    Real f[3], ma[3];
    for (int i = 0; i < 3; ++i) {
      f[i] = phi[0] * n[i] + phi[1] * t1[i] + phi[2] * t2[i];
      ma[i] = mom[0] * n[i] + mom[1] * t1[i] + mom[2] * t2[i];
    }
    const Real dxf[3] = {dx[1] * f[2] - dx[2] * f[1], dx[2] * f[0] - dx[0] * f[2],
                         dx[0] * f[1] - dx[1] * f[0]};
    for (int i = 0; i < 3; ++i) {
      out.force[i][l] = f[i];
      out.torque_b[i][l] = ma[i] - dxf[i];
      out.torque_a[i][l] = -ma[i];
      out.n[i][l] = n[i];
      out.t1[i][l] = t1[i];
    }
    if constexpr (kEnergy) out.energy[l] = energy_from_change(hl, kn, al, jm, du, dd);
    out.dissipated[l] = softening_dissipation(hl, kn, jm, du, dd);
  }
}

void held_block_baseline(const HeldInputs& in, const Index* list, Index count, bool energy,
                         HeldLanes* lanes, HeldOutputs& out) {
  if (energy) return held_block_lanes<true>(in, list, count, *lanes, out);
  held_block_lanes<false>(in, list, count, *lanes, out);
}
#if RCDEM_SIMD_MULTIVERSION
RCDEM_SIMD_TARGET_AVX2 void held_block_avx2(const HeldInputs& in, const Index* list, Index count,
                                            bool energy, HeldLanes* lanes, HeldOutputs& out) {
  if (energy) return held_block_lanes<true>(in, list, count, *lanes, out);
  held_block_lanes<false>(in, list, count, *lanes, out);
}
RCDEM_SIMD_TARGET_AVX512 void held_block_avx512(const HeldInputs& in, const Index* list,
                                                Index count, bool energy, HeldLanes* lanes,
                                                HeldOutputs& out) {
  if (energy) return held_block_lanes<true>(in, list, count, *lanes, out);
  held_block_lanes<false>(in, list, count, *lanes, out);
}
#endif

}  // namespace

void broken_point_sums(CondensedSums& sums, Index c, const Vec3& xa0,
                       const LocalPointRecord* points, Index begin, Index end,
                       const std::uint8_t* broken) {
  store_point_sums(
      sums, static_cast<std::size_t>(c), begin, end, xa0,
      [&](Index m) { return points[m].constants.kn; },
      [&](Index m) { return Vec3(points[m].x0, points[m].y0, points[m].z0); },
      [&](Index m) { return broken[m - begin] == 0; });
}

bool broken_and_open(const PlanePointState& s) {
  return s.damage >= 1 && s.fn == 0 && s.fs.x == 0 && s.fs.y == 0;
}

bool on_normal_envelope(const LocalPointRecord& p) {
  const PlanePointState& st = p.history;
  const LocalPointConstants& k = p.constants;
  return st.damage > 0 && st.damage < 1 && st.un == st.un_max &&
         st.fn == (1 - st.damage) * k.fn_max && !(k.ks * k.ks * st.us_max_sq > k.c_max * k.c_max);
}

namespace {

// Such a point's rooms (along n to a margin short of u_nu, D = 1; across as point_rooms'), beta
// and gamma; false if its damage is not its opening's alone or a room is not positive.
bool softening_rooms(const LocalPointRecord& p, Real u_nu, Real& room_n, Real& room_s, Real& beta,
                     Real& gamma) {
  const PlanePointState& st = p.history;
  const LocalPointConstants& k = p.constants;
  const Real u_n0 = k.fn_max / k.kn;
  if (st.damage != softening_damage(st.un_max, u_n0, u_nu)) return false;
  Real unused;
  point_rooms(p, unused, room_s);
  room_n = kLimitMargin * u_nu - st.un - kRounding * (u_nu + std::abs(st.un));
  beta = u_n0 / (u_nu - u_n0);
  gamma = (k.c_max / k.ks) / (u_nu - u_n0);
  return room_n > 0 && room_s > 0 && beta > 0;
}

// The points' kinds: broken and open (b), softening along the envelope (s) or inside it (i); a
// contact holds i and b, or s and b. Then the rooms, the slope (every softening point's beta the
// same to kSameSlope) and the shrink. Returns false if the contact cannot be held.
constexpr Real kSameSlope = 1e-9;
bool point_kinds(const LocalPointRecord* points, Index begin, Index end, Real u_nu,
                 std::uint8_t* kind, Real& open_margin, Real& room_n, Real& room_s, Real& slope_n,
                 Real& shrink_s) {
  bool inside = false, softening = false;
  open_margin = -1;  // no broken or softening point: no test of their opening
  for (Index m = begin; m < end; ++m) {
    const PlanePointState& st = points[m].history;
    char k = 'i';
    if (st.damage >= 1) {
      if (!broken_and_open(st)) return false;
      k = 'b';
    } else if (st.damage > 0 && u_nu > 0 && on_normal_envelope(points[m])) {
      k = 's';
    }
    if ((k == 'i' && softening) || (k == 's' && inside)) return false;
    inside |= k == 'i';
    softening |= k == 's';
    kind[m - begin] = static_cast<std::uint8_t>(k);
    // The step's opening must exceed what rounding in the law's un - un_old could turn over.
    if (k != 'i') open_margin = std::max(open_margin, kRounding * std::abs(st.un));
  }
  room_n = room_s = std::numeric_limits<Real>::infinity();
  slope_n = 1;
  shrink_s = 0;
  for (Index m = begin; m < end; ++m) {
    const char k = static_cast<char>(kind[m - begin]);
    if (k == 'b') continue;
    Real rn, rs, beta, gamma;
    if (k == 's') {
      if (!softening_rooms(points[m], u_nu, rn, rs, beta, gamma)) return false;
      if (slope_n < 0 && !(std::abs(beta + slope_n) <= kSameSlope * beta)) return false;
      slope_n = -beta;
      shrink_s = std::max(shrink_s, gamma);
    } else {
      point_rooms(points[m], rn, rs);
      // NaN rooms (a zero strength) fail here too.
      if (!(rn > 0 && rs > 0)) return false;
    }
    room_n = std::min(room_n, rn);
    room_s = std::min(room_s, rs);
  }
  return true;
}

}  // namespace

bool hold_contact(CondensedSums& sums, Index c, const ContactFrame& f, const Real* pose, Index a,
                  Index b, const LocalPointRecord* points, Index begin, Index end, Real u_nu,
                  HeldSums& h) {
  constexpr Index kMaxPoints = 64;
  std::uint8_t kind[kMaxPoints], broken[kMaxPoints];
  if (end - begin > kMaxPoints) return false;
  Real open_margin, room_n, room_s, slope_n, shrink_s;
  if (!point_kinds(points, begin, end, u_nu, kind, open_margin, room_n, room_s, slope_n, shrink_s))
    return false;
  for (Index m = 0; m < end - begin; ++m) broken[m] = kind[m] == 'b';
  if (open_margin >= 0) broken_point_sums(sums, c, f.xa0, points, begin, end, broken);
  const auto i = static_cast<std::size_t>(c);
  const Real rc[3] = {sums.centroid[0][i], sums.centroid[1][i], sums.centroid[2][i]};
  HeldSums s{};
  for (Index m = begin; m < end; ++m) {
    const LocalPointRecord& p = points[m];
    const PlanePointState& st = p.history;
    const Real phi[3] = {-st.fn, st.fs.x, st.fs.y};
    const Real rho[3] = {p.x0 - f.xa0.x() - rc[0], p.y0 - f.xa0.y() - rc[1],
                         p.z0 - f.xa0.z() - rc[2]};
    for (int k = 0; k < 3; ++k) {
      s.phi0[k] += phi[k];
      for (int j = 0; j < 3; ++j) s.q[3 * k + j] += rho[k] * phi[j];
    }
    s.energy0 += 0.5 * st.fn * st.fn / p.constants.kn + 0.5 * st.fs.squaredNorm() / p.constants.ks;
  }
  s.room_n = room_n;
  s.room_s = room_s;
  s.open_margin = open_margin;  // the last step's du_cn and dD row n: zero at the entry
  s.slope_n = slope_n;
  s.shrink_s = shrink_s;
  // The entry's kinematics with the kernel's arithmetic (not f's), so that the change is exactly
  // zero at the entry's poses.
  kinematics_at_poses(sums, i, f.n, f.t1, pose, a, b, s.disp0, s.disp);
  h = s;
  return true;
}

void evaluate_held_block(const HeldInputs& in, const Index* list, Index count, bool energy,
                         HeldOutputs& out) {
  // The list run to a whole number of the widest lanes (8 doubles), its last contact repeated
  // (outputs past `count` are not read): a list's last few contacts otherwise went through the
  // loop's scalar remainder, one at a time, at the cost of a vector iteration each.
  constexpr Index kWidest = 8;
  static_assert(HeldContacts::kBlock % kWidest == 0, "a block is whole vectors");
  Index padded[HeldContacts::kBlock];
  const Index whole = (count + kWidest - 1) / kWidest * kWidest;
  std::copy(list, list + count, padded);
  std::fill(padded + count, padded + whole, count > 0 ? list[count - 1] : 0);
  HeldLanes lanes;
#if RCDEM_SIMD_MULTIVERSION
  switch (simd_level()) {
    case SimdLevel::Avx512:
      return held_block_avx512(in, padded, whole, energy, &lanes, out);
    case SimdLevel::Avx2:
      return held_block_avx2(in, padded, whole, energy, &lanes, out);
    case SimdLevel::Baseline:
      break;
  }
#endif
  held_block_baseline(in, padded, whole, energy, &lanes, out);
}

Real held_strain_energy(const CondensedSums& s, Index c, const HeldSums& h, const Vec3& n,
                        const Vec3& t1, const Real* pose, Index a, Index b) {
  // The kernel's arithmetic (held_block_lanes), on the stored frame: the same bits.
  const auto i = static_cast<std::size_t>(c);
  Real disp0[3], disp[9];
  kinematics_at_poses(s, i, n, t1, pose, a, b, disp0, disp);
  const Real rc[3] = {s.centroid[0][i], s.centroid[1][i], s.centroid[2][i]};
  const Real* hd = reinterpret_cast<const Real*>(&h);
  Real du[3], dd[9];
  change_since_entry(hd, rc, disp0, disp, du, dd);
  const Real jm[9] = {s.j[0][i], s.j[3][i], s.j[4][i], s.j[3][i], s.j[1][i],
                      s.j[5][i], s.j[4][i], s.j[5][i], s.j[2][i]};
  return energy_from_change(hd, s.k_n[i], s.alpha[i], jm, du, dd);
}

}  // namespace rcdem
