#pragma once
// The explicit integration of every body (SPEC 5): Cundall's local non-viscous damping and the
// leap-frog, the concrete particles in SIMD lanes (sphere_update.hpp), the bars' cylinders one by
// one, a body whose motion a part prescribes (step_part.hpp, PrescribedMotion) moved at that
// velocity. It leaves per body what the step's ledger and instability check read (BodyStepSums).
#include "rcdem/core/types.hpp"
#include "rcdem/solver/body_step_sums.hpp"
#include "rcdem/solver/step_part.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

class Integrator {
 public:
  Integrator(const Bodies& bodies, const PrescribedMotion& motion, Real damping)
      : sums_(BodyStepSums::build(bodies, motion.slot)), damping_(damping) {}

  // Advances every body over dt; true if a body jumped (moved a twentieth of its size or turned
  // kStableTurnLimit in one step: a numerical instability).
  bool advance(Bodies& b, const PrescribedMotion& motion, Real dt);
  // Whether a body jumped at the last advance (from the blocks' flags and the cylinders').
  bool jumped() const;
  // The first body that jumped at the last advance, or -1.
  Index first_jumped() const;
  // This step's damping work and the kinetic energy, summed in a fixed order.
  void add_energies(Real& damping_work, Real& kinetic) const;

  // A distributed run: this rank advances the spheres [begin, end) (whole blocks) and every body
  // past the spheres; the others' arrive by RankExchange::share_spheres.
  void share_spheres(Index begin, Index end) {
    sphere_begin_ = begin;
    sphere_end_ = end;
  }
  BodyStepSums& step_sums() { return sums_; }

  Real damping() const { return damping_; }
  void set_damping(Real alpha) { damping_ = alpha; }
  Real& damping_ref() { return damping_; }  // the checkpoint's "solver" record
  const Real& damping_ref() const { return damping_; }

  // The checkpoint's "bodies.step" (core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    BodyStepSums::serialize(ar, s.sums_);
  }

 private:
  void advance_cylinder(Bodies& b, Index i, const PrescribedMotion& motion, Real dt);

  BodyStepSums sums_;
  Real damping_;
  Index sphere_begin_ = 0, sphere_end_ = -1;  // -1: every sphere
};

}  // namespace rcdem
