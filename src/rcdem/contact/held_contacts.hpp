#pragma once
// Damaged contacts held to their sums while every point stays inside its envelope (issue 43).
//
// Most damaged contacts of a cracked specimen unload or reload elastically: a crack has opened
// and the material around it relaxes. Under BL (BilinearSoftening::update) a point whose step
// caps neither force, raises no damage and grows no maximum the damage reads is linear in the
// step's displacement, with slopes kn and ks from where it stands:
//   phi_J(t) = phi_J(t0) - kn_J L du_J,   L = diag(1, alpha, alpha),  du_J = u_J(t) - u_J(t0),
// phi = (-fn, fs_1, fs_2) the force on B in the contact's frame. In the frame, u_J = disp0 +
// disp r_J (contact_loop.hpp), so du_J = d0 + dD r_J with d0 = disp0(t) - disp0(t0) and
// dD = disp(t) - disp(t0), whatever the frame did in between (the points keep their shear
// history as frame components). With r_J = r_c + rho_J around the kn-weighted centroid
// (sum kn rho = 0), K and J = sum kn rho rho^T as the intact condensation keeps them
// (elastic_condensation.hpp), and du_c = d0 + dD r_c:
//   force      sum phi_J = Phi0 - K L du_c
//   moment     sum a_J x phi_J = a_c x sum phi + eps : (arm Q) - eps : (arm J dD^T L),
//              a_c = disp0 / 2 + arm r_c,  Q = sum rho_J phi_J(t0)^T,
//              (eps : P)_i = P_jk - P_kj for (i, j, k) cyclic,
//   energy     sum E_J = E0 - (Phi0 . du_c + sum_ik dD_ik Q_ki)
//                          + (K du_c^T L du_c + sum_k L_k (dD J dD^T)_kk) / 2,
// E_J = phi_J^T L^-1 phi_J / (2 kn_J), the spring energy (SPEC 11). Phi0, Q, E0, the entry's
// disp0, disp, the two rooms, the broken points' margin and last step (5 numbers, below), the
// normal slope and the shear room's shrink (below) are 34 numbers per held contact, against 6
// points' 768 bytes.
//
// Whether the points stay linear is decided by a bound, row by row of dD: with rho_J = r_J - r_c,
// |du_Jn - du_cn| <= |dD_n| max|rho| = e_n (dD_n: dD's row along n) and |du_Js - du_cs| <=
// |dD_s|_F max|rho| = e_s (dD_s: its t1, t2 rows; the Frobenius norm bounds their spectral
// norm), and the contact stays held while du_cn + e_n < room_n and |du_cs| + e_s < room_s, the
// smallest room of its points at entry:
//   normal: to the cap, ((1 - D) fn_max - fn) / kn, and to the largest un the damage does not
//           read, max(un_max, u_n0) - un (below u_n0 = fn_max / kn no damage is read);
//   shear:  to the cap without friction, ((1 - D) c_max - |fs|) / ks (friction only widens it),
//           and max(|us|_max, u_s0) - |us|.
// A broken point (D = 1) has no room, but under BL its force is kn min(0, un - M), M its largest
// opening since it broke, and its shear cap mu max(0, -fn) is then 0: at its largest opening
// (fn = 0, fs = 0) it carries nothing for as long as each step opens it further, whatever the
// path. So a contact whose broken points are open is held too, with K, r_c, J and the radius of
// its points that carry force (broken_point_sums), while each step's change of du_cn less
// |change of dD_n| max|rho| is at least open_margin (a part in 1e9 of their opening, for rounding
// in the law's un - un_old); that needs the last held step's du_cn and dD_n.
// A point softening along its normal envelope (0 < D < 1 from its largest opening alone, fn =
// (1 - D) fn_max at un = un_max, its shear below the cap) follows, while each step opens it
// further, fn = fn_max (u_nu - un) / (u_nu - u_n0): a line of slope -beta kn, beta = u_n0 /
// (u_nu - u_n0), the same for every point of a contact (u_n0 = sigma_n,t / (E_bar / L)). So a
// contact whose unbroken points all soften can be held (solver.hold_softening_contacts, on by
// default) with L = diag(-beta, alpha, alpha) (slope_n = -beta) and the energy's normal row's
// work and quadratic term scaled by -beta and beta^2; each
// step its points dissipate sum (fn_J(t - 1) + fn_J(t)) / 2 (1 + beta) delta_J
// (softening_dissipation in the kernel, the law's trapezoid); its rooms are to u_nu (D = 1)
// along n and, across, to the shear cap, which shrinks by shrink_s = (c_max / ks) / (u_nu - u_n0)
// per unit of opening; and it stays held only while every point keeps opening (the broken
// points' test below). Points inside the envelope and softening ones are not held together.
// A held contact that leaves its room first has its points brought up to the last step (one
// elastic update from the entry's histories: what the point loop would have stored, to rounding,
// except a maximum below its elastic limit, which nothing reads and which a held step does not
// raise), then goes through its points as usual. Held or not, the law's result is the same to
// rounding; what changes is the arithmetic (sums, and the catch-up's one step for several).
// Reading the points (snapshots, checkpoints: Simulation::contacts()) brings a held contact's
// points up to the last evaluation the same way, from their histories at entry, which the read
// first saves (HeldContacts::entry), and keeps it held: when it leaves its room, its points are
// caught up from those saved histories again. So a run computes the same bits whenever and however
// often it is read, and a checkpoint holds the held contacts, their sums and their entry histories
// beside the points (caught up): a restart continues with the bits of the run that wrote it.
// An intact contact (every point D = 0) that the condensation's bound sends to its points, near an
// elastic limit, is held the same way (solver.hold_intact_contacts, on by default): its points are
// inside their envelope, with rooms to their caps from where they stand at entry, and the change
// since entry is bounded row by row, where the condensation bounds the total displacement with the
// whole relative rotation. It stays held, and is not condensed, until it leaves its room (such
// holds mostly last: docs/model.md).
// Where softening contacts open only a few steps at a time (a beam's crack opens in bursts and its
// faces ring), a softening hold costs more (entry sums, catch-up) than the visits it saves: a
// contact whose softening hold ends within kShortSofteningHold steps is not held as softening
// again for its next kSofteningBackoff visits (HeldContacts::softening_clock; it may still be held
// with its points inside their envelope). The clock is state: a checkpoint keeps it.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "rcdem/contact/contact_frame.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"

namespace rcdem {

struct CondensedSums;  // elastic_condensation.hpp

// What a held contact keeps from its entry (formulas above), frame components.
struct HeldSums {
  Real phi0[3];         // sum phi_J(t0)
  Real q[9];            // Q = sum rho_J phi_J(t0)^T, row-major: q[3 k + i] = sum rho_k phi_i
  Real energy0;         // sum E_J(t0)
  Real room_n, room_s;  // the bound's rooms
  Real disp0[3];        // disp0(t0)
  Real disp[9];         // disp(t0), row-major
  // With broken points: the smallest step of their opening the bound accepts (>= 0; -1 without
  // broken points: no test), and the last held step's du_cn and dD's row along n.
  Real open_margin;
  Real last_du_n;
  Real last_dd_n[3];
  // The points' normal slope in units of their kn: 1 for points inside their envelope, -beta for
  // points softening along it (below); and how much of the shear room a unit of normal opening
  // takes (gamma: 0 inside the envelope).
  Real slope_n;
  Real shrink_s;
};

// The checkpoint's columns of HeldSums (core/archive.hpp), in its order.
template <class Record, class S>
void archive_fields(Record& r, S& h) {
  for (auto& v : h.phi0) r.put(named("phi0", "N", v));
  for (auto& v : h.q) r.put(named("q", "N*m", v));
  r.put(named("energy0", "J", h.energy0));
  r.put(named("room_n", "m", h.room_n));
  r.put(named("room_s", "m", h.room_s));
  for (auto& v : h.disp0) r.put(named("disp0", "m", v));
  for (auto& v : h.disp) r.put(named("disp", "1", v));
  r.put(named("open_margin", "m", h.open_margin));
  r.put(named("last_du_n", "m", h.last_du_n));
  for (auto& v : h.last_dd_n) r.put(named("last_dd_n", "1", v));
  r.put(named("slope_n", "1", h.slope_n));
  r.put(named("shrink_s", "1", h.shrink_s));
}

// A softening hold that ends within this many steps is short; its contact then waits this many
// visits before it is held as softening again (above).
inline constexpr std::int16_t kShortSofteningHold = 8;
inline constexpr std::int16_t kSofteningBackoff = 64;

// The held contacts of a network: a flag per contact and, per block of kBlock contacts (the
// contact loop's, CondensedBlock::kSize) that has held one, the block's sums (allocated by the
// thread that evaluates the block, so only cracked regions take memory).
struct HeldContacts {
  static constexpr Index kBlock = 128;
  bool enabled = false;                      // solver.hold_unloading_contacts
  bool softening = false;                    // solver.hold_softening_contacts
  bool intact = false;                       // solver.hold_intact_contacts
  std::vector<std::uint8_t> held;            // per contact
  std::vector<std::vector<HeldSums>> block;  // per block, empty until one of its contacts is held
  // Per contact: held as softening for this many steps so far (> 0, at most kShortSofteningHold),
  // visits left before it may be held as softening again (< 0), or neither (0). Only with
  // `softening`.
  std::vector<std::int16_t> softening_clock;
  // A read's catch-up (above): per contact, whether its points' histories at entry are in `entry`
  // (changed only between steps, looked up by the step's threads); and whether every held
  // contact's points stand at the last evaluation (a read since the last step: a release then
  // has nothing to catch up).
  std::vector<std::uint8_t> saved;
  std::unordered_map<Index, std::vector<PlanePointState>> entry;
  bool current = false;

  void resize(Index contacts);
  HeldSums& sums(Index c);  // c's, its block allocated if needed (only its block's thread)
  const HeldSums& sums(Index c) const;
  Index count() const;
  void clear();  // nothing held, every clock at 0 (the sums stay allocated)
  // Before a read's catch-up, for each held contact: its points' histories (`points`: all of the
  // network's, point_begin: where each contact's start) put back to its entry's, or saved. Between
  // steps only.
  void keep_entries(const Index* point_begin, LocalPointRecord* points);
  // Contact c is released: its entry's histories put back into `points` (its own, `count` of them)
  // if a read saved them and `points` is given.
  void take_entry(Index c, LocalPointRecord* points, Index count);
};

// A held contact and its sums, and a point's history at its contact's entry (the checkpoint's
// "contacts.held" and "contacts.held.entry").
struct HeldRow {
  std::int64_t contact = 0;
  HeldSums sums{};
};
struct HeldEntryRow {
  std::int64_t point = 0;
  PlanePointState history{};
};
// A contact's non-zero softening clock (HeldContacts::softening_clock; "contacts.held.clock").
struct SofteningClockRow {
  std::int64_t contact = 0;
  std::int64_t clock = 0;
};
// Everything a checkpoint keeps of the held contacts, each list ascending by contact or point.
struct HeldRows {
  std::vector<HeldRow> held;
  std::vector<HeldEntryRow> entry;
  std::vector<SofteningClockRow> clock;
};

// A broken point at its largest opening: under BL its force is kn min(0, un - M), M its largest
// opening since it broke, and its shear cap (1 - D) c_max + mu max(0, -fn) is then 0, so while its
// opening keeps growing it carries nothing, whatever the path.
bool broken_and_open(const PlanePointState& s);

// A point softening along its normal envelope at its largest opening, with no shear damage read
// (BilinearSoftening::update): while it keeps opening its force is fn = fn_max (u_nu - un) /
// (u_nu - u_n0), slope -beta kn with beta = u_n0 / (u_nu - u_n0), and its shear cap (1 - D) c_max
// shrinks by gamma = (c_max / ks) / (u_nu - u_n0) times ks per unit of opening. Tested without a
// division first: most contacts that fail to be held fail here.
bool on_normal_envelope(const LocalPointRecord& p);

// Whether contact c, just evaluated through its points in the frame `f` at the poses `pose` (A = a,
// B = b), is held from the next step: every point of it inside its room or broken and open (at its
// largest opening: fn = 0, fs = 0), or, with u_nu > 0 (the law's ultimate opening; 0: not
// allowed), every unbroken one softening along its normal envelope; if so, h receives its sums,
// and with broken points the condensation's K, centroid, J and radius of c become those of its
// points that carry force (broken_point_sums).
bool hold_contact(CondensedSums& sums, Index c, const ContactFrame& f, const Real* pose, Index a,
                  Index b, const LocalPointRecord* points, Index begin, Index end, Real u_nu,
                  HeldSums& h);

// Contact c's K, centroid, J and radius in `sums` (elastic_condensation.hpp) over its points
// [begin, end) that are not broken (`broken[m - begin]`), the radius over all of them, A's centre
// at t = 0 being xa0: what a held contact with broken points is linear in (held_contacts.hpp).
// Once a point of a contact is broken the contact is never intact again, so nothing else reads
// these numbers of c; every hold of c sets them anew (and a checkpoint's restore, from the entry).
void broken_point_sums(CondensedSums& sums, Index c, const Vec3& xa0,
                       const LocalPointRecord* points, Index begin, Index end,
                       const std::uint8_t* broken);

// What the held contacts' kernel reads: the block's contacts from `begin`, their sums.
struct HeldInputs {
  const CondensedSums& sums;
  const Index* particle_a;
  const Index* particle_b;
  const Real* pose;    // the bodies' centres and orientations at the evaluation (BodyPoses)
  const Real* w;       // the bodies' angular velocities, 3 per body
  const Real* normal;  // the stored frames' axes, 3 per contact (ContactState)
  const Real* tangent;
  Real dt;
  const Real* held_sums;  // the block's HeldSums, HeldContacts::kBlock of them, as doubles
  Index begin;            // the block's first contact
};

// Per entry of the list: force on B, torques, the turned frame's axes, the energy (if asked) and
// whether the contact stays held (1) or must go through its points (0: nothing here is used).
struct HeldOutputs {
  Real force[3][HeldContacts::kBlock], torque_b[3][HeldContacts::kBlock],
      torque_a[3][HeldContacts::kBlock];
  Real n[3][HeldContacts::kBlock], t1[3][HeldContacts::kBlock];
  Real energy[HeldContacts::kBlock];
  Real du_n[HeldContacts::kBlock], dd_n[3][HeldContacts::kBlock];  // HeldSums::last_*
  Real dissipated[HeldContacts::kBlock];  // by damage this step (softening points; else 0)
  std::int64_t kept[HeldContacts::kBlock];
};

// The held contacts `list[0, count)` of a block (formulas above) in SIMD lanes, 8 at a time with
// AVX-512: the frame turned from the stored one, the kinematics from the poses, the bound, the
// force and moment from the sums (and each one's energy with `energy`). The same instructions for
// a contact whatever its place in the list, so the bits do not depend on the thread count.
void evaluate_held_block(const HeldInputs& in, const Index* list, Index count, bool energy,
                         HeldOutputs& out);

// The elastic energy of held contact c in its stored frame (n, t1) at the poses of the evaluation
// that stored it (A = a, B = b), from its sums: the kernel's bits.
Real held_strain_energy(const CondensedSums& sums, Index c, const HeldSums& h, const Vec3& n,
                        const Vec3& t1, const Real* pose, Index a, Index b);

}  // namespace rcdem
