#pragma once
// EL law (SPEC 5, used for the steel-concrete interface): (1)-(2) with no strength limit and no
// damage. Displacements and their maxima are still accumulated so that output reads the same for
// either law.
#include <algorithm>

#include "rcdem/contact/laws/local_point_state.hpp"
#include "rcdem/contact/laws/shear_envelope.hpp"

namespace rcdem {

struct Elastic {
  // What a point keeps between updates (V: Vec3, or PlaneVec in the contact loop).
  template <typename V>
  using State = BasicPointState<V>;

  // Its contacts always go through their points: with no limit, a contact would never leave
  // the condensed kernel, whose catch-up assumes BL's intact branch.
  static constexpr bool kCondensable = false;

  template <typename V>
  Real elastic_energy(const LocalPointConstants& c, const State<V>& s) const {
    return spring_energy(c, s);
  }

  // Same contract as BilinearSoftening::update; never dissipates.
  template <typename V>
  [[gnu::always_inline]] LawResult update(const LocalPointConstants& c, State<V>& s,
                                          Real u_n, const V& u_s) const {
    const Real dun = u_n - s.un;
    const V dus = u_s - s.us;
    s.un = u_n;
    s.us = u_s;
    s.un_max = std::max(s.un_max, s.un);
    s.us_max_sq = std::max(s.us_max_sq, s.us.squaredNorm());
    s.fn += c.kn * dun;  // (1), tension positive
    s.fs -= c.ks * dus;  // (2), resists B's slip relative to A
    return {};
  }
};

}  // namespace rcdem
