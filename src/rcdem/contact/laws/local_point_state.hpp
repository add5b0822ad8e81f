#pragma once
// What a contact law reads and writes at one local contact point (SPEC 1, 4-5). Plain data, so
// the solver can keep it in flat arrays and the laws stay free functions of it.
#include <concepts>
#include <type_traits>

#include "rcdem/core/archive.hpp"
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

// History of one local point, SI units: the point state of the laws here (each law names its
// state as `State<V>`; a law with other history declares its own struct, law_registry.hpp).
// Tension-positive (SPEC 1): un > 0 is opening, fn > 0 is tension. The force on particle B is
// (-fn n + fs) and on A its opposite, so an opening pulls B back and fs opposes B's slip relative
// to A. V: Vec3, or PlaneVec in the contact loop. D comes first: a point record
// (local_point_records.hpp) puts the state after its 56 read-only bytes, so D, written only when it
// grows, shares their cache line and the rest, written every visit, fills the next one.
template <typename V>
struct BasicPointState {
  Real damage = 0;     // D in [0, 1], never decreasing (S4)
  Real fn = 0;         // normal force [N], tension positive
  V fs = V::Zero();    // shear force [N], in the contact plane
  Real un = 0;         // accumulated normal displacement [m], opening positive
  V us = V::Zero();    // accumulated shear displacement [m], in the contact plane
  Real un_max = 0;     // historical maximum of un (>= 0), drives D_n (S3)
  Real us_max_sq = 0;  // historical maximum of |us|^2 (squared: no root per step), drives D_s (S3)
};
using LocalPointState = BasicPointState<Vec3>;
using PlanePointState = BasicPointState<PlaneVec>;

// A plane vector as checkpoint columns (core/archive.hpp): t1, then t2.
template <class Record, class P>
requires std::same_as<std::remove_const_t<P>, PlaneVec>
void archive_fields(Record& r, P& v) {
  r.put(named("t1", "", v.x));
  r.put(named("t2", "", v.y));
}

template <class T>
inline constexpr bool kIsPointState = false;
template <class V>
inline constexpr bool kIsPointState<BasicPointState<V>> = true;

// A point's history as checkpoint columns (core/archive.hpp), in this order, for both V: the plate
// contacts' (Vec3) and the point records' (PlaneVec, the shear vectors as frame components).
template <class Record, class S>
requires kIsPointState<std::remove_const_t<S>>
void archive_fields(Record& r, S& s) {
  r.put(named("fn", "N", s.fn));
  r.put(named("fs", "N", s.fs));
  r.put(named("un", "m", s.un));
  r.put(named("us", "m", s.us));
  r.put(named("un_max", "m", s.un_max));
  r.put(named("us_max_sq", "m^2", s.us_max_sq));
  r.put(named("damage", "1", s.damage));
}

// The state into a stored one: D is written only when it changed (it only grows), so the cache
// line it shares with read-only data (above) is not dirtied by most visits.
template <typename V>
[[gnu::always_inline]] inline void store_state(BasicPointState<V>& to,
                                               const BasicPointState<V>& s) {
  to.fn = s.fn;
  to.fs = s.fs;
  to.un = s.un;
  to.us = s.us;
  to.un_max = s.un_max;
  to.us_max_sq = s.us_max_sq;
  if (s.damage != to.damage) to.damage = s.damage;
}

// A point's frame-component state in the world form's type: shear vectors (t1, t2, 0)
// (ContactState::to_world turns them into world vectors).
inline LocalPointState in_frame_components(const PlanePointState& p) {
  LocalPointState s;
  s.fn = p.fn;
  s.fs = Vec3(p.fs.x, p.fs.y, 0.0);
  s.un = p.un;
  s.us = Vec3(p.us.x, p.us.y, 0.0);
  s.un_max = p.un_max;
  s.us_max_sq = p.us_max_sq;
  s.damage = p.damage;
  return s;
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
