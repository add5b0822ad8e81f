#pragma once
// Bilinear softening law BL (paper §2.4, SPEC 5) at one local contact point.
//
// Damage in each direction comes from the historical maximum of that direction's accumulated
// displacement (S3) and softens linearly, so a point opened monotonically follows the triangle
// (0, 0) -> (u_n0, F_n,max) -> (u_nu, 0), whose area is
//   0.5 F_n,max u_nu = 0.5 (sigma_n,t A_c)(2 G_f,n / sigma_n,t) = G_f,n A_c
// exactly; likewise G_f,s A_c in shear at fn = 0. Inside the envelope (S5) the point is elastic
// with kn, ks, so unloading keeps slope kn and reloading meets the envelope where it left it.
#include <algorithm>
#include <cmath>

#include "rcdem/contact/laws/local_point_state.hpp"
#include "rcdem/contact/laws/shear_envelope.hpp"

namespace rcdem {

// Damage in one direction (S3). A brittle direction (u_ult <= u_0) breaks at once past u_0.
// Written with negated comparisons so that a degenerate limit (NaN from a zero strength) yields
// full damage rather than a NaN that would spread through the forces.
inline Real softening_damage(Real u_max, Real u_0, Real u_ult) {
  if (!(u_max > u_0)) return 0;
  if (!(u_ult > u_0)) return 1;
  return std::min<Real>(1, (u_max - u_0) / (u_ult - u_0));
}

struct BilinearSoftening {
  // What a point keeps between updates (V: Vec3, or PlaneVec in the contact loop).
  template <typename V>
  using State = BasicPointState<V>;

  Real sigma_nt = 0;  // contact tensile strength sigma_n,t [Pa], (5)
  Real tau = 0;       // contact cohesion tau [Pa], (6)
  Real G_fn = 0;      // tensile fracture energy [J/m^2]
  Real G_fs = 0;      // shear fracture energy [J/m^2]
  Real mu_c = 0;      // friction coefficient, (S5)

  // An intact point below its limits holds fn = kn u_n, fs = -ks u_s exactly (the trial forces
  // below): its contact may be evaluated from its sums (law_registry.hpp, kCondensableLaw).
  static constexpr bool kCondensable = true;
  // A point that caps neither force and raises neither maximum the damage reads is linear in the
  // step's displacement with slopes kn, ks from where it stands (unloading keeps kn): its damaged
  // contact may be held to its sums while that lasts (held_contacts.hpp, kHoldableLaw). So may
  // one whose broken points keep opening: such a point's force is kn min(0, un - M), M its largest
  // opening since it broke, and its shear cap then 0 (update below, cap_shear); and one whose
  // points soften along the normal envelope while they keep opening: fn = (1 - D) fn_max is then
  // linear in un, with slope -kn u_n0 / (u_nu - u_n0).
  static constexpr bool kHoldable = true;

  // Ultimate displacements of the softening triangles (S2); independent of the point's area.
  Real u_nu() const { return 2 * G_fn / sigma_nt; }
  Real u_su() const { return 2 * G_fs / tau; }

  // The elastic energy held at the point (SPEC 11): fn^2/2kn + |fs|^2/2ks (unloading keeps kn).
  template <typename V>
  Real elastic_energy(const LocalPointConstants& c, const State<V>& s) const {
    return spring_energy(c, s);
  }

  // Advances the point to the accumulated relative displacement u_n along n (opening positive)
  // and u_s in the current contact plane (SPEC 4; the increments of the step are u - s.u). The
  // caller has already rotated s.fs and s.us into that plane. Requires c.kn > 0 and c.ks > 0.
  // V: Vec3, or PlaneVec (frame components) in the contact loop.
  template <typename V>
  [[gnu::always_inline]] LawResult update(const LocalPointConstants& c, State<V>& s, Real u_n,
                                          const V& u_s) const {
    const Real fn_old = s.fn;
    const V fs_old = s.fs;
    const Real dun = u_n - s.un;
    const V dus = u_s - s.us;
    s.un = u_n;
    s.us = u_s;
    // (1)-(2) in tension-positive form: fs resists the slip of B relative to A. A point that has
    // never left the elastic range (D = 0) holds exactly fn = kn un and fs = -ks us, so its trial
    // forces are taken from the accumulated displacement: the same numbers as the increments'
    // sum, but independent of how the stored history was rounded, which lets the contact loop
    // skip such points' histories altogether (contact/elastic_condensation.hpp).
    const bool intact = s.damage == 0;
    const Real fn_trial = intact ? c.kn * u_n : fn_old + c.kn * dun;
    const V fs_trial = intact ? V(-c.ks * u_s) : V(fs_old - c.ks * dus);

    // The elastic path, which most points take most steps, needs no square root and no division:
    // limits are compared as kn u_max > F_max and on squared lengths.
    // The damage is a function of the two maxima alone (S3)-(S4), and every update leaves
    // D >= that function, so a step that raises neither maximum leaves D as it is: a damaged
    // point inside its envelope (most of a cracked beam's points, most steps) skips the divisions
    // and the square root below, with the same result to the bit.
    const Real us_sq = s.us.squaredNorm();
    const bool max_grew = s.un > s.un_max || us_sq > s.us_max_sq;
    s.un_max = std::max(s.un_max, s.un);
    s.us_max_sq = std::max(s.us_max_sq, us_sq);
    // A broken point (D = 1, the most (S4) gives) keeps D = 1 whatever its maxima: an opening
    // crack's points, whose opening grows every step, skip the divisions and the square root.
    Real d = s.damage;
    const bool past_n = c.kn * s.un_max > c.fn_max;
    const bool past_s = c.ks * c.ks * s.us_max_sq > c.c_max * c.c_max;
    if (max_grew && d < 1 && (past_n || past_s)) {
      const Real d_n = past_n ? softening_damage(s.un_max, c.fn_max / c.kn, u_nu()) : 0;  // (S3)
      const Real d_s =
          past_s ? softening_damage(std::sqrt(s.us_max_sq), c.c_max / c.ks, u_su()) : 0;  // (S3)
      d = std::max(d, std::min<Real>(1, d_n + d_s));                                      // (S4)
    }

    LawResult r;
    r.damage_grew = d > s.damage;
    s.damage = d;

    // (S5): tension capped, compression unlimited; the shear cap uses the new normal force so
    // that friction follows the compression actually carried at the end of the step.
    const Real fn_cap = (1 - d) * c.fn_max;
    const bool normal_capped = fn_trial > fn_cap;
    s.fn = normal_capped ? fn_cap : fn_trial;

    // Dissipation = work - dE, with E = fn^2/2kn + |fs|^2/2ks: in the normal direction, since
    // dun = (fn_trial - fn_old)/kn, it is f_eff (fn_trial - fn_new)/kn, with f_eff the mean force
    // over the inelastic part of the step (the trapezoid along the softening line, where it is
    // exact; fn_new where the step first rises elastically to the cap: first yield, or reopening
    // from compression). So dissipation is >= 0 for any step, exactly zero for an elastic one,
    // and converges to the exact value. The shear part: shear_envelope.hpp.
    if (normal_capped) {
      const Real f_eff = 0.5 * (std::max(fn_old, s.fn) + s.fn);
      r.dissipated += f_eff * (fn_trial - s.fn) / c.kn;
    }
    s.fs = cap_shear(c, mu_c, d, s.fn, fs_old, fs_trial, r);
    return r;
  }
};

}  // namespace rcdem
