#pragma once
// cos a and sin a / a for an angle that is nearly always tiny (a contact pair's spin in one step,
// a body's turn: ~1e-6 rad), from their Taylor series, which are exact to rounding below 0.1 rad
// (the first omitted terms, a^10 / 10! and a^10 / 11!, are < 3e-17) and need no square root, sine
// or division. The range covers every turn of a stable step (the solver stops a run whose bodies
// turn 0.05 rad in one), so the bodies' update needs no other branch in its SIMD lanes
// (solver/sphere_update.cpp). Callers take libm's above the threshold.
#include "rcdem/core/types.hpp"

namespace rcdem {

// True where the series below hold: a^2 < 1e-2.
[[gnu::always_inline]] inline bool is_small_angle(Real a2) { return a2 < 1e-2; }

// From a^2 alone: cos a and sin a / a (Horner, through a^8).
[[gnu::always_inline]] inline void small_angle_cos_sinc(Real a2, Real& c, Real& sinc) {
  c = 1.0 - a2 * (0.5 - a2 * (1.0 / 24.0 - a2 * (1.0 / 720.0 - a2 * (1.0 / 40320.0))));
  sinc = 1.0 - a2 * (1.0 / 6.0 - a2 * (1.0 / 120.0 - a2 * (1.0 / 5040.0 - a2 * (1.0 / 362880.0))));
}

}  // namespace rcdem
