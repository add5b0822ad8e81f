#pragma once
// What a contact law reads and writes at one local contact point (SPEC 1, 4-5). Plain data, so
// the solver can keep it in flat arrays and the laws stay free functions of it.
#include "rcdem/core/types.hpp"

namespace rcdem {

// History of one local point, SI units. Tension-positive (SPEC 1): un > 0 is opening, fn > 0 is
// tension. The force on particle B is (-fn n + fs) and on A its opposite, so an opening pulls B
// back and fs opposes B's slip relative to A.
struct LocalPointState {
  Real fn = 0;             // normal force [N], tension positive
  Vec3 fs = Vec3::Zero();  // shear force [N], in the contact plane
  Real un = 0;             // accumulated normal displacement [m], opening positive
  Vec3 us = Vec3::Zero();  // accumulated shear displacement [m], in the contact plane
  Real un_max = 0;         // historical maximum of un (>= 0), drives D_n (S3)
  Real us_max_sq = 0;      // historical maximum of |us|^2 (squared: no root per step), drives D_s (S3)
  Real damage = 0;         // D in [0, 1], never decreasing (S4)
};

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
