#pragma once
// cos a and sin a / a for an angle that is nearly always tiny (a contact pair's spin in one step,
// a body's turn: ~1e-6 rad), from their Taylor series, which are exact to rounding below 1e-3 rad
// (the first omitted terms are < 2e-21) and need no square root, sine or division. Callers take
// libm's above the threshold.
#include "rcdem/core/types.hpp"

namespace rcdem {

// True where the series below hold: a^2 < 1e-6.
[[gnu::always_inline]] inline bool is_small_angle(Real a2) { return a2 < 1e-6; }

// From a^2 alone: cos a and sin a / a.
[[gnu::always_inline]] inline void small_angle_cos_sinc(Real a2, Real& c, Real& sinc) {
  c = 1.0 - a2 * (0.5 - a2 * (1.0 / 24.0));
  sinc = 1.0 - a2 * (1.0 / 6.0 - a2 * (1.0 / 120.0));
}

}  // namespace rcdem
