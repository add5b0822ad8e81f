#pragma once
// Exponential softening with scalar damage at one local point: the damage law of YADE's concrete
// particle model (CPM: V. Smilauer, "Cohesive particle model using the discrete element method on
// the Yade platform", PhD thesis, CTU Prague and Universite Grenoble I, 2010, the damage evolution
// function with its exponential law; in YADE, CpmPhys::funcG with damLaw = 1):
//   D(kappa) = 1 - (u_0 / kappa) exp(-(kappa - u_0) / u_f)  for kappa > u_0, else 0,
// with kappa the historical maximum of the opening u_n (CPM's kappa_D) and u_0 = F_n,max / k_n.
//
// The normal force is secant, as in CPM: fn = (1 - D) kn u_n in tension and kn u_n in compression
// (a crack closes with the full stiffness), so a damaged point unloads to the origin. A point
// opened monotonically follows F_n,max exp(-(u_n - u_0) / u_f) past its peak, whose curve encloses
// F_n,max (u_0 / 2 + u_f). CPM takes u_f as a material constant; here it is regularised by the
// fracture energy, u_f = G_f,n / sigma_n,t - u_0 / 2, so the area is G_f,n A_c exactly, as BL's
// triangle (S2). Where G_f,n / sigma_n,t <= u_0 / 2 no softening curve can hold that little energy
// and the point breaks at u_0, as a brittle BL direction does.
//
// Shear: (S5)'s envelope, cohesion (1 - D) c_max plus Coulomb friction (shear_envelope.hpp), as
// CPM's Mohr-Coulomb yield with its cohesion reduced by (1 - omega). Only the opening damages, as
// in CPM; G_f,s is not used.
#include <algorithm>
#include <cmath>

#include "rcdem/contact/laws/local_point_state.hpp"
#include "rcdem/contact/laws/shear_envelope.hpp"

namespace rcdem {

struct ExponentialSoftening {
  // What a point keeps between updates (V: Vec3, or PlaneVec in the contact loop).
  template <typename V>
  using State = BasicPointState<V>;

  Real sigma_nt = 0;  // contact tensile strength sigma_n,t [Pa], (5)
  Real G_fn = 0;      // tensile fracture energy [J/m^2]
  Real mu_c = 0;      // friction coefficient, (S5)
  // The cohesion enters through each point's C_max = tau A_c (6); G_f,s is not used.

  // A point may slip in shear while D = 0, so D = 0 does not mean fs = -ks u_s: never condensed.
  static constexpr bool kCondensable = false;

  // The decay length u_f that makes the curve's area G_f,n A_c (<= 0: brittle).
  Real decay_length(Real u_0) const { return G_fn / sigma_nt - 0.5 * u_0; }

  // D at the historical maximum opening kappa. Negated comparisons: a degenerate limit (NaN from a
  // zero strength) gives full damage, not a NaN.
  static Real damage_at(Real kappa, Real u_0, Real u_f) {
    if (!(kappa > u_0)) return 0;
    if (!(u_f > 0)) return 1;
    return 1 - (u_0 / kappa) * std::exp(-(kappa - u_0) / u_f);
  }

  // The energy released by the damage from the start to kappa: the integral of Y dD with
  // Y = kn kappa^2 / 2 (the secant law's energy release rate), in closed form
  //   kn u_0 / 2 [(2 u_f + u_0)(1 - e^(-s/u_f)) - s e^(-s/u_f)],  s = kappa - u_0,
  // which tends to kn u_0 (u_f + u_0 / 2) = G_f,n A_c. Exact, so the dissipation booked per step
  // does not depend on the step.
  static Real released(Real kn, Real kappa, Real u_0, Real u_f) {
    if (!(kappa > u_0)) return 0;
    if (!(u_f > 0)) return 0.5 * kn * kappa * kappa;
    const Real s = kappa - u_0;
    return 0.5 * kn * u_0 * (-(2 * u_f + u_0) * std::expm1(-s / u_f) - s * std::exp(-s / u_f));
  }

  // The elastic energy held at the point (SPEC 11): fn u_n / 2 on the secant, |fs|^2 / 2ks.
  template <typename V>
  Real elastic_energy(const LocalPointConstants& c, const State<V>& s) const {
    return 0.5 * s.fn * s.un + shear_energy(c, s.fs);
  }

  // Same contract as BilinearSoftening::update.
  template <typename V>
  [[gnu::always_inline]] LawResult update(const LocalPointConstants& c, State<V>& s,
                                          Real u_n, const V& u_s) const {
    const V fs_old = s.fs;
    const V fs_trial = V(fs_old - c.ks * (u_s - s.us));  // (2), tension-positive form
    s.un = u_n;
    s.us = u_s;
    const Real kappa_old = s.un_max;
    s.un_max = std::max(s.un_max, u_n);
    s.us_max_sq = std::max(s.us_max_sq, s.us.squaredNorm());
    LawResult r;
    if (s.un_max > kappa_old && s.damage < 1) {
      const Real u_0 = c.fn_max / c.kn;
      const Real u_f = decay_length(u_0);
      const Real d = damage_at(s.un_max, u_0, u_f);
      if (d > s.damage) {
        r.damage_grew = true;
        r.dissipated = std::max<Real>(
            0, released(c.kn, s.un_max, u_0, u_f) - released(c.kn, kappa_old, u_0, u_f));
        s.damage = d;
      }
    }
    s.fn = u_n > 0 ? (1 - s.damage) * c.kn * u_n : c.kn * u_n;  // (1), secant in tension
    s.fs = cap_shear(c, mu_c, s.damage, s.fn, fs_old, fs_trial, r);
    return r;
  }
};

}  // namespace rcdem
