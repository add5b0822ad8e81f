#pragma once
// EL law (SPEC 5, used for the steel-concrete interface): (1)-(2) with no strength limit and no
// damage. Displacements and their maxima are still accumulated so that output reads the same for
// either law.
#include <algorithm>

#include "rcdem/contact/laws/local_point_state.hpp"

namespace rcdem {

struct Elastic {
  // Same contract as BilinearSoftening::update; never dissipates.
  template <typename V>
  [[gnu::always_inline]] LawResult update(const LocalPointConstants& c, BasicPointState<V>& s,
                                          Real u_n, const V& u_s) const {
    s.un = u_n;
    s.us = u_s;
    s.un_max = std::max(s.un_max, s.un);
    s.us_max_sq = std::max(s.us_max_sq, s.us.squaredNorm());
    s.fn = c.kn * (u_n - s.pn);  // (1), tension positive; the offsets stay 0 under this law
    s.fs = -c.ks * (u_s - s.ps);  // (2), resists B's slip relative to A
    return {};
  }
};

}  // namespace rcdem
