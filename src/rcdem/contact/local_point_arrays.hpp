#pragma once
// The histories of a network's local points as a structure of arrays (one array per quantity,
// shear vectors as their two components in the contact's frame): the contact loop streams each
// array once (its inner loop over a contact's points runs in SIMD lanes for the EL law). The
// forces are not stored: they follow from the displacements and offsets (local_point_state.hpp),
// and state() forms them for readers.
#include <array>
#include <vector>

#include "rcdem/contact/laws/local_point_state.hpp"

namespace rcdem {

// The arrays as raw pointers, for the contact loop's SIMD lanes: a point's history in and out.
struct LocalPointPointers {
  Real *pn, *ps1, *ps2, *un, *us1, *us2, *un_max, *us_max_sq, *damage;

  [[gnu::always_inline]] PlanePointState load(Index m) const {
    PlanePointState s;
    s.pn = pn[m];
    s.ps = {ps1[m], ps2[m]};
    s.un = un[m];
    s.us = {us1[m], us2[m]};
    s.un_max = un_max[m];
    s.us_max_sq = us_max_sq[m];
    s.damage = damage[m];
    return s;
  }
  [[gnu::always_inline]] void store(Index m, const PlanePointState& s) const {
    pn[m] = s.pn;
    ps1[m] = s.ps.x;
    ps2[m] = s.ps.y;
    un[m] = s.un;
    us1[m] = s.us.x;
    us2[m] = s.us.y;
    un_max[m] = s.un_max;
    us_max_sq[m] = s.us_max_sq;
    damage[m] = s.damage;
  }
};

struct LocalPointArrays {
  std::vector<Real> pn, ps1, ps2, un, us1, us2, un_max, us_max_sq, damage;

  Index size() const { return static_cast<Index>(pn.size()); }
  LocalPointPointers pointers() {
    return {pn.data(),  ps1.data(),    ps2.data(),       un.data(),    us1.data(),
            us2.data(), un_max.data(), us_max_sq.data(), damage.data()};
  }
  // The nine arrays in the order above (for whole-array work: sizing, checkpoints).
  std::array<std::vector<Real>*, 9> arrays() {
    return {&pn, &ps1, &ps2, &un, &us1, &us2, &un_max, &us_max_sq, &damage};
  }
  std::array<const std::vector<Real>*, 9> arrays() const {
    return {&pn, &ps1, &ps2, &un, &us1, &us2, &un_max, &us_max_sq, &damage};
  }
  void assign(std::size_t n) {
    for (auto* a : arrays()) a->assign(n, 0.0);
  }
  // Point m with its forces formed from its constants c, shear vectors as frame components
  // (t1, t2, 0) (ContactState::to_world turns them into world vectors).
  LocalPointState state(Index m, const LocalPointConstants& c) const {
    LocalPointState s;
    s.pn = pn[m];
    s.ps = Vec3(ps1[m], ps2[m], 0.0);
    s.un = un[m];
    s.us = Vec3(us1[m], us2[m], 0.0);
    s.fn = c.kn * (s.un - s.pn);
    s.fs = -c.ks * (s.us - s.ps);
    s.un_max = un_max[m];
    s.us_max_sq = us_max_sq[m];
    s.damage = damage[m];
    return s;
  }
};

}  // namespace rcdem
