#pragma once
// Selective mass scaling (SPEC 6's "optional mass scaling", in the form explicit codes use for
// quasi-static runs: LS-DYNA's DT2MS, Abaqus's variable mass scaling to a target increment).
//
// SPEC 6's step is the shortest of the bodies' own estimates sqrt(m / sum k), so the lightest,
// stiffest few bodies set it for all. Multiplying one body's mass and moments of inertia by f
// scales its whole 6x6 estimate (solver/body_stiffness.hpp) by exactly sqrt(f), so the bodies
// below a common target T can be raised to it with f_i = (T / dt_i)^2, at an added mass of
// sum m_i (f_i - 1). The plan takes the longest T whose added mass stays within a given fraction
// of the total: a quasi-static result does not depend on inertia (the rate check of SPEC 6 is
// what shows that), and a small fraction of added mass, spread over the stiffest bodies, changes
// it less than the loading rate does. Uniform mass scaling by s is, by contrast, exactly the same
// run as loading sqrt(s) times faster (time rescales; the Cundall damping does not see it).
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem {

struct MassScalingPlan {
  Real time_step = 0;        // every body's estimate after the scaling is at least this
  Real unscaled_step = 0;    // the shortest estimate before it
  std::vector<Real> step;    // each body's own estimate before it (as given)
  std::vector<Real> factor;  // per body, >= 1 (1: unchanged)
  Index bodies_scaled = 0;
  Real largest_factor = 1;
  Real added_mass = 0;  // kg
  Real total_mass = 0;  // kg, before the scaling

  Real added_fraction() const { return total_mass > 0 ? added_mass / total_mass : 0; }
};

// `step`: each body's own stable estimate (infinite for a body without springs); `mass`: its
// mass. `added_mass_limit`: the largest fraction of the total mass to add (0: no scaling, the
// plan is the identity). The target is exact: the added mass equals the limit unless every body
// already reaches the target or all of them are raised.
MassScalingPlan plan_selective_mass_scaling(const std::vector<Real>& step,
                                            const std::vector<Real>& mass, Real added_mass_limit);

}  // namespace rcdem
