#pragma once
// (S5)'s shear envelope, shared by the softening laws: the shear force is capped at
// (1 - D) c_max + mu_c max(0, -fn), cohesion lost with the damage and Coulomb friction on the
// compression the point carries at the end of the step, and what the cap takes is dissipated.
#include <algorithm>
#include <cmath>

#include "rcdem/contact/laws/local_point_state.hpp"

namespace rcdem {

// Returns the shear force after the cap, from the trial force fs_trial = fs_old - ks dus, with D
// and fn already updated; adds the step's shear dissipation to r. V: Vec3 or PlaneVec.
//
// Dissipation = work - dE, with E = |fs|^2/2ks and the work of the relative slip -fs . dus, is
// f_eff . (fs_trial - fs_new)/ks, with f_eff the mean force over the inelastic part of the step:
// the trapezoid (fs_old + fs_new)/2 while the force falls (where it is exact), fs_new where the
// step first rises elastically to the cap, where the trapezoid would book the elastic rise as
// inelastic.
template <typename V>
[[gnu::always_inline]] inline V cap_shear(const LocalPointConstants& c, Real mu_c, Real d, Real fn,
                                          const V& fs_old, const V& fs_trial, LawResult& r) {
  const Real friction = mu_c * std::max<Real>(0, -fn);
  const Real fs_cap = (1 - d) * c.c_max + friction;  // >= 0
  const Real fs_trial_sq = fs_trial.squaredNorm();
  // The capped force as a select before the branch: with an early return instead, BL's point
  // update compiled to a slower path (bench/RESULTS.md, "Architecture").
  const bool capped = fs_trial_sq > fs_cap * fs_cap;
  const V fs = capped ? V((fs_cap / std::sqrt(fs_trial_sq)) * fs_trial) : fs_trial;
  if (!capped) return fs;
  const V f_eff = fs_old.squaredNorm() > fs.squaredNorm() ? V(0.5 * (fs_old + fs)) : fs;
  // max(0, .): only a step reversing the slip by more than the elastic range, impossible at a
  // stable time step, could make the trapezoid negative here.
  const Real dissipated_shear = std::max<Real>(0, f_eff.dot(fs_trial - fs) / c.ks);
  r.dissipated += dissipated_shear;
  // Split by the make-up of the cap the force ended on: friction's share of it.
  if (fs_cap > 0) r.dissipated_friction = dissipated_shear * (friction / fs_cap);
  return fs;
}

// The elastic energy of the shear springs, |fs|^2 / 2ks (SPEC 11).
template <typename V>
[[gnu::always_inline]] inline Real shear_energy(const LocalPointConstants& c, const V& fs) {
  return 0.5 * fs.squaredNorm() / c.ks;
}

// A point whose springs unload with kn and ks (BL, EL): fn^2/2kn + |fs|^2/2ks (SPEC 11).
template <typename V>
Real spring_energy(const LocalPointConstants& c, const BasicPointState<V>& s) {
  return 0.5 * s.fn * s.fn / c.kn + shear_energy(c, s.fs);
}

}  // namespace rcdem
