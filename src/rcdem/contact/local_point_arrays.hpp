#pragma once
// The histories of a network's local points as a structure of arrays (one array per quantity,
// shear vectors as their two components in the contact's frame): the contact loop streams each
// array once (its inner loop over a contact's points runs in SIMD lanes for the EL law).
#include <array>
#include <vector>

#include "rcdem/contact/laws/local_point_state.hpp"

namespace rcdem {

// The arrays as raw pointers, for the contact loop's SIMD lanes: a point's history in and out.
struct LocalPointPointers {
  Real *fn, *fs1, *fs2, *un, *us1, *us2, *un_max, *us_max_sq, *damage;

  [[gnu::always_inline]] PlanePointState load(Index m) const {
    PlanePointState s;
    s.fn = fn[m];
    s.fs = {fs1[m], fs2[m]};
    s.un = un[m];
    s.us = {us1[m], us2[m]};
    s.un_max = un_max[m];
    s.us_max_sq = us_max_sq[m];
    s.damage = damage[m];
    return s;
  }
  [[gnu::always_inline]] void store(Index m, const PlanePointState& s) const {
    fn[m] = s.fn;
    fs1[m] = s.fs.x;
    fs2[m] = s.fs.y;
    un[m] = s.un;
    us1[m] = s.us.x;
    us2[m] = s.us.y;
    un_max[m] = s.un_max;
    us_max_sq[m] = s.us_max_sq;
    damage[m] = s.damage;
  }
};

struct LocalPointArrays {
  std::vector<Real> fn, fs1, fs2, un, us1, us2, un_max, us_max_sq, damage;

  Index size() const { return static_cast<Index>(fn.size()); }
  LocalPointPointers pointers() {
    return {fn.data(),  fs1.data(),    fs2.data(),       un.data(),    us1.data(),
            us2.data(), un_max.data(), us_max_sq.data(), damage.data()};
  }
  // The nine arrays in the order above (for whole-array work: sizing, checkpoints).
  std::array<std::vector<Real>*, 9> arrays() {
    return {&fn, &fs1, &fs2, &un, &us1, &us2, &un_max, &us_max_sq, &damage};
  }
  std::array<const std::vector<Real>*, 9> arrays() const {
    return {&fn, &fs1, &fs2, &un, &us1, &us2, &un_max, &us_max_sq, &damage};
  }
  void assign(std::size_t n) {
    for (auto* a : arrays()) a->assign(n, 0.0);
  }
  // Point m with its shear vectors as frame components (t1, t2, 0) (ContactState::to_world turns
  // them into world vectors).
  LocalPointState operator[](Index m) const {
    LocalPointState s;
    s.fn = fn[m];
    s.fs = Vec3(fs1[m], fs2[m], 0.0);
    s.un = un[m];
    s.us = Vec3(us1[m], us2[m], 0.0);
    s.un_max = un_max[m];
    s.us_max_sq = us_max_sq[m];
    s.damage = damage[m];
    return s;
  }
};

}  // namespace rcdem
