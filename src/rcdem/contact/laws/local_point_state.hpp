#pragma once
// What a contact law reads and writes at one local contact point (SPEC 1, 4-5). Plain data, so
// the solver can keep it in flat arrays and the laws stay free functions of it.
#include <concepts>
#include <type_traits>

#include "rcdem/core/types.hpp"

namespace rcdem {

// A vector in the contact plane as its components along the frame's axes (t1, t2): the form the
// contact loop keeps, two numbers instead of three and plain scalars a vectorising compiler can
// put in SIMD lanes. The laws are written once for it and for Vec3.
struct PlaneVec {
  Real x = 0, y = 0;
  static PlaneVec Zero() { return {}; }
  Real squaredNorm() const { return x * x + y * y; }
  Real dot(const PlaneVec& b) const { return x * b.x + y * b.y; }
  PlaneVec& operator+=(const PlaneVec& b) {
    x += b.x;
    y += b.y;
    return *this;
  }
  PlaneVec& operator-=(const PlaneVec& b) {
    x -= b.x;
    y -= b.y;
    return *this;
  }
  friend PlaneVec operator+(PlaneVec a, const PlaneVec& b) { return a += b; }
  friend PlaneVec operator-(PlaneVec a, const PlaneVec& b) { return a -= b; }
  friend PlaneVec operator*(Real s, const PlaneVec& a) { return {s * a.x, s * a.y}; }
};

// History of one local point, SI units. Tension-positive (SPEC 1): un > 0 is opening, fn > 0 is
// tension. The force on particle B is (-fn n + fs) and on A its opposite, so an opening pulls B
// back and fs opposes B's slip relative to A. V: Vec3, or PlaneVec in the contact loop.
template <typename V>
struct BasicPointState {
  Real fn = 0;         // normal force [N], tension positive
  V fs = V::Zero();    // shear force [N], in the contact plane
  Real un = 0;         // accumulated normal displacement [m], opening positive
  V us = V::Zero();    // accumulated shear displacement [m], in the contact plane
  Real un_max = 0;     // historical maximum of un (>= 0), drives D_n (S3)
  Real us_max_sq = 0;  // historical maximum of |us|^2 (squared: no root per step), drives D_s (S3)
  Real damage = 0;     // D in [0, 1], never decreasing (S4)
};
using LocalPointState = BasicPointState<Vec3>;
using PlanePointState = BasicPointState<PlaneVec>;

// A point's history as checkpoint columns (core/archive.hpp; plate contacts), in this order.
template <class Record, class S>
requires std::same_as<std::remove_const_t<S>, LocalPointState>
void archive_fields(Record& r, S& s) {
  r.put(s.fn);
  r.put(s.fs);
  r.put(s.un);
  r.put(s.us);
  r.put(s.un_max);
  r.put(s.us_max_sq);
  r.put(s.damage);
}

// Per-point constants: stiffness (3)-(4) and strength (5)-(6). The law derives its elastic limits
// u_n0 = fn_max / kn and u_s0 = c_max / ks from them; kn and ks must be > 0.
struct LocalPointConstants {
  Real kn = 0;      // (3) [N/m]
  Real ks = 0;      // (4) [N/m]
  Real fn_max = 0;  // (5) [N]
  Real c_max = 0;   // (6) [N]
};

// What one update did, for the energy balance (SPEC 11) and the damage counters.
struct LawResult {
  // Energy dissipated at the point during the update [J], >= 0: the work of the relative
  // displacement on the point minus the change of its elastic energy. Exactly zero for an elastic
  // update. (How the step's work is integrated: see BilinearSoftening::update.)
  Real dissipated = 0;
  // The part of `dissipated` due to Coulomb friction mu_c max(0, -fn) (S5); the rest is damage.
  Real dissipated_friction = 0;
  bool damage_grew = false;
};

}  // namespace rcdem
