#pragma once
// SPEC 6's better time step: dt_crit = 2 / omega_max of the assembled system, omega_max^2 the
// largest eigenvalue of M^-1/2 K M^-1/2 (solver/assembled_stiffness.hpp), found by Lanczos
// iteration on the operator the assembly applies.
//
// What the value is worth (docs/model.md 4):
// - The Lanczos value theta is a Rayleigh quotient, so theta <= lambda_max, and it stops when its
//   residual |A v - theta v| is below `tolerance` theta: an eigenvalue lies within that of theta
//   (and, the top of the spectrum being found first, in practice lambda_max itself: the tests
//   compare with dense eigenvalues).
// - It is never below the largest body block's lambda (body_stiffness.hpp), a proven lower bound
//   of lambda_max; should Lanczos not converge, the proven upper bound 2 x that block lambda is
//   used instead (a shorter, safe step), and the caller says so.
// - K is the initial stiffness with every plate contact closed. The BL law's damage and breakage,
//   friction's sliding and a plate contact's opening only lower the tangent stiffness, and a
//   pulled bar's prescribed motion removes degrees of freedom, which cannot raise omega_max
//   (Rayleigh): the step stays stable for the whole run. What could raise it (contact between
//   bodies that share no facet, bars or plates stiffer than at t = 0) the model does not have.
#include <cmath>
#include <string>

#include "rcdem/solver/assembled_stiffness.hpp"

namespace rcdem {

struct CriticalTimeStep {
  Real omega_max = 0.0;  // rad/s
  Real time_step = 0.0;  // 2 / omega_max, undamped
  Real residual = 0.0;   // of the Ritz pair, relative to omega_max^2
  long long operator_applications = 0;
  bool converged = false;
  // In words, for the run's header: the value and how it was found.
  std::string how() const;
};

// With local non-viscous (Cundall) damping alpha the critical step is shorter:
// 2 / (omega_max sqrt(1 + alpha)). The damping takes alpha |F| off every force component against
// the velocity, so while a body moves away from equilibrium (force against the velocity) it feels
// the force (1 + alpha) times over: in that half of each oscillation every spring is 1 + alpha
// times as stiff. Measured on a glued box (tests/verification/test_critical_time_step.cpp): stable
// up to 0.876 and 0.767 of 2 / omega_max with alpha 0.3 and 0.7, against 1 / sqrt(1 + alpha) =
// 0.877 and 0.767. (Near that limit a cracking run is still stable but no longer accurate:
// docs/model.md 6.)
inline Real damped_critical_time_step(Real undamped, Real alpha) {
  return undamped / std::sqrt(1.0 + alpha);
}

// lambda_block: the largest eigenvalue of any one body's block scaled by its mass and inertia
// (1 / its per-body estimate squared).
CriticalTimeStep assembled_critical_time_step(const AssembledStiffness& k, Real lambda_block,
                                              Real tolerance = 1e-4);

}  // namespace rcdem
