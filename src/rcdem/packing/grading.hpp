#pragma once
// Diameter distributions of SPEC 2: uniform in diameter (default), or a Fuller grading with mass
// passing P(d) = (d / d_max)^q, whose number density is then proportional to d^(q - 4).
#include "rcdem/config/scenario.hpp"
#include "rcdem/core/rng.hpp"
#include "rcdem/core/types.hpp"

namespace rcdem {

struct DiameterDistribution {
  Grading grading = Grading::Uniform;
  Real d_min = 0.0, d_max = 0.0;
  Real fuller_exponent = 0.5;

  Real quantile(Real u) const;  // inverse CDF of the number distribution, u in [0, 1)
  Real sample(Rng& rng) const { return quantile(rng.uniform()); }
  Real mean_volume() const;  // E[pi d^3 / 6], for size estimates and tests
};

}  // namespace rcdem
