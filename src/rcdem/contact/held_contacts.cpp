#include "rcdem/contact/held_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rcdem/contact/elastic_condensation.hpp"

namespace rcdem {

static_assert(HeldContacts::kBlock == CondensedBlock::kSize, "held sums are kept per block of the loop");

void HeldContacts::resize(Index contacts) {
  held.assign(static_cast<std::size_t>(contacts), 0);
  block.assign(static_cast<std::size_t>((contacts + kBlock - 1) /
                                        kBlock),
               {});
}

HeldSums& HeldContacts::sums(Index c) {
  std::vector<HeldSums>& b = block[static_cast<std::size_t>(c / kBlock)];
  if (b.empty()) b.resize(kBlock);
  return b[static_cast<std::size_t>(c % kBlock)];
}

const HeldSums& HeldContacts::sums(Index c) const {
  return block[static_cast<std::size_t>(c / kBlock)]
              [static_cast<std::size_t>(c % kBlock)];
}

Index HeldContacts::count() const {
  return static_cast<Index>(std::count(held.begin(), held.end(), std::uint8_t{1}));
}

void HeldContacts::clear() { std::fill(held.begin(), held.end(), std::uint8_t{0}); }

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

// du_c = d0 + dD r_c and dD (row-major) since the entry, in the frame f.
struct Change {
  Real du[3], dd[9];
};

Change change_since_entry(const CondensedSums& sums, std::size_t i, const HeldSums& h,
                          const ContactFrame& f) {
  Change ch;
  const Real rc[3] = {sums.centroid[0][i], sums.centroid[1][i], sums.centroid[2][i]};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) ch.dd[3 * r + k] = f.disp(r, k) - h.disp[3 * r + k];
    ch.du[r] = (f.disp0[r] - h.disp0[r]) +
               (ch.dd[3 * r] * rc[0] + ch.dd[3 * r + 1] * rc[1] + ch.dd[3 * r + 2] * rc[2]);
  }
  return ch;
}

// J = sum kn rho rho^T, row-major.
void j_matrix(const CondensedSums& sums, std::size_t i, Real* jm) {
  const Real j[9] = {sums.j[0][i], sums.j[3][i], sums.j[4][i], sums.j[3][i], sums.j[1][i],
                     sums.j[5][i], sums.j[4][i], sums.j[5][i], sums.j[2][i]};
  std::copy(j, j + 9, jm);
}

Real energy_from_change(const CondensedSums& sums, std::size_t i, const HeldSums& h,
                        const Change& ch) {
  const Real l[3] = {1.0, sums.alpha[i], sums.alpha[i]};
  Real jm[9];
  j_matrix(sums, i, jm);
  Real work = 0.0, quad = 0.0;
  for (int k = 0; k < 3; ++k) {
    work += h.phi0[k] * ch.du[k];
    quad += sums.k_n[i] * l[k] * ch.du[k] * ch.du[k];
    Real djd = 0.0;  // (dD J dD^T)_kk
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) djd += ch.dd[3 * k + a] * jm[3 * a + b] * ch.dd[3 * k + b];
    quad += l[k] * djd;
    for (int m = 0; m < 3; ++m) work += ch.dd[3 * k + m] * h.q[3 * m + k];  // dD_km Q_mk
  }
  return h.energy0 - work + 0.5 * quad;
}

}  // namespace

bool hold_contact(const CondensedSums& sums, Index c, const ContactFrame& f,
                  const LocalPointRecord* points, Index begin, Index end, HeldSums& h) {
  const auto i = static_cast<std::size_t>(c);
  const Real rc[3] = {sums.centroid[0][i], sums.centroid[1][i], sums.centroid[2][i]};
  Real room_n = std::numeric_limits<Real>::infinity(), room_s = room_n;
  HeldSums s{};
  for (Index m = begin; m < end; ++m) {
    const LocalPointRecord& p = points[m];
    Real rn, rs;
    point_rooms(p, rn, rs);
    room_n = std::min(room_n, rn);
    room_s = std::min(room_s, rs);
    const PlanePointState& st = p.history;
    const Real phi[3] = {-st.fn, st.fs.x, st.fs.y};
    const Real rho[3] = {p.x0 - f.xa0.x() - rc[0], p.y0 - f.xa0.y() - rc[1],
                         p.z0 - f.xa0.z() - rc[2]};
    for (int k = 0; k < 3; ++k) {
      s.phi0[k] += phi[k];
      for (int a = 0; a < 3; ++a) s.q[3 * k + a] += rho[k] * phi[a];
    }
    s.energy0 += 0.5 * st.fn * st.fn / p.constants.kn + 0.5 * st.fs.squaredNorm() / p.constants.ks;
  }
  // NaN rooms (a zero strength) fail here too.
  if (!(room_n > 0 && room_s > 0)) return false;
  s.room_n = room_n;
  s.room_s = room_s;
  for (int r = 0; r < 3; ++r) {
    s.disp0[r] = f.disp0[r];
    for (int k = 0; k < 3; ++k) s.disp[3 * r + k] = f.disp(r, k);
  }
  h = s;
  return true;
}

bool evaluate_held(const CondensedSums& sums, Index c, const HeldSums& h, const ContactFrame& f,
                   ContactState& cs, Real* energy) {
  const auto i = static_cast<std::size_t>(c);
  const Change ch = change_since_entry(sums, i, h, f);
  Real dd_sq = 0.0;
  for (const Real v : ch.dd) dd_sq += v * v;
  const Real spread = std::sqrt(dd_sq) * sums.radius[i];
  if (!(ch.du[0] + spread < h.room_n)) return false;
  if (!(std::sqrt(ch.du[1] * ch.du[1] + ch.du[2] * ch.du[2]) + spread < h.room_s)) return false;

  const Real k = sums.k_n[i];
  const Real l[3] = {1.0, sums.alpha[i], sums.alpha[i]};
  const Real rc[3] = {sums.centroid[0][i], sums.centroid[1][i], sums.centroid[2][i]};
  Real jm[9];
  j_matrix(sums, i, jm);
  Real phi[3], ac[3];
  for (int r = 0; r < 3; ++r) {
    phi[r] = h.phi0[r] - k * l[r] * ch.du[r];
    ac[r] = 0.5 * f.disp0[r] + f.arm(r, 0) * rc[0] + f.arm(r, 1) * rc[1] + f.arm(r, 2) * rc[2];
  }
  // aq = arm Q, p = arm J dD^T L (row-major).
  Real aj[9], aq[9], p[9];
  for (int r = 0; r < 3; ++r)
    for (int m = 0; m < 3; ++m) {
      aj[3 * r + m] = f.arm(r, 0) * jm[m] + f.arm(r, 1) * jm[3 + m] + f.arm(r, 2) * jm[6 + m];
      aq[3 * r + m] = f.arm(r, 0) * h.q[m] + f.arm(r, 1) * h.q[3 + m] + f.arm(r, 2) * h.q[6 + m];
    }
  for (int r = 0; r < 3; ++r)
    for (int m = 0; m < 3; ++m)
      p[3 * r + m] = l[m] * (aj[3 * r] * ch.dd[3 * m] + aj[3 * r + 1] * ch.dd[3 * m + 1] +
                             aj[3 * r + 2] * ch.dd[3 * m + 2]);
  const Real mom[3] = {
      ac[1] * phi[2] - ac[2] * phi[1] + (aq[5] - aq[7]) - (p[5] - p[7]),
      ac[2] * phi[0] - ac[0] * phi[2] + (aq[6] - aq[2]) - (p[6] - p[2]),
      ac[0] * phi[1] - ac[1] * phi[0] + (aq[1] - aq[3]) - (p[1] - p[3])};
  const Vec3 force = phi[0] * f.n + phi[1] * f.t1 + phi[2] * f.t2;
  const Vec3 moment_a = mom[0] * f.n + mom[1] * f.t1 + mom[2] * f.t2;
  cs.force_b[c] = force;
  cs.torque_b[c] = moment_a - f.dx.cross(force);
  cs.torque_a[c] = -moment_a;
  cs.dissipated_damage[c] = 0.0;
  cs.dissipated_friction[c] = 0.0;
  if (energy) *energy = energy_from_change(sums, i, h, ch);
  return true;
}

Real held_strain_energy(const CondensedSums& sums, Index c, const HeldSums& h,
                        const ContactFrame& f) {
  const auto i = static_cast<std::size_t>(c);
  return energy_from_change(sums, i, h, change_since_entry(sums, i, h, f));
}

}  // namespace rcdem
