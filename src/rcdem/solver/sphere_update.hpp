#pragma once
// One leap-frog step of the concrete particles (SPEC 6), the bulk of the bodies: isotropic
// inertia, not driven. The same update as Integrator::advance_cylinder (solver/integrator.cpp):
// Cundall's local damping, L += T dt, q <- exp(w dt) q, the leap-frog kinetic energy; written on
// plain scalars so that GCC runs it 8 bodies at a time: the general loop, with its branches for
// cylinders and pulled bars and its quaternion products through Eigen, was a fifth of an elastic
// step.
#include <cmath>
#include <cstdint>

#include "rcdem/core/types.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

// A body that turns more than this in one step is unstable (Simulation stops the run) [rad].
inline constexpr Real kStableTurnLimit = 0.05;

// Cundall's local non-viscous damping (SPEC 6): alpha |F| against the velocity, per component
// (the same for a torque against the angular velocity). Shared with the cylinders' loop.
[[gnu::always_inline]] inline Real cundall_damping(Real alpha, Real force, Real velocity) {
  return alpha * std::abs(force) * (velocity > 0 ? 1.0 : velocity < 0 ? -1.0 : 0.0);
}

struct SphereStepOutputs {
  Real* damping_work;    // per body: the energy damping removed this step [J]
  Real* kinetic;         // per body: 1/2 m v(n-1/2).v(n+1/2) and its rotational analogue [J]
  std::int64_t* jumped;  // per body, 0 or 1: moved more than 0.05 radius or turned 0.05 rad
                         // (a byte per body does not fit lanes of doubles)
};

// Bodies [begin, end), every one a sphere (inertia x = y = z) that is not driven. The turn
// exp(w dt) comes from the small-angle series alone (core/small_angle.hpp): it holds well beyond
// the turn that flags a body `jumped` (and stops the run).
void advance_spheres(Bodies& b, Index begin, Index end, Real dt, Real damping,
                     const SphereStepOutputs& out);

}  // namespace rcdem
