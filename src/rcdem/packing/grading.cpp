#include "rcdem/packing/grading.hpp"

#include <cmath>

namespace rcdem {

Real DiameterDistribution::quantile(Real u) const {
  if (grading == Grading::Uniform || d_max <= d_min) return d_min + (d_max - d_min) * u;
  // Inverse of the CDF of n(d) ~ d^(q-4) on [d_min, d_max].
  const Real p = fuller_exponent - 3.0;
  if (std::abs(p) < 1e-12) return d_min * std::pow(d_max / d_min, u);
  const Real a = std::pow(d_min, p), b = std::pow(d_max, p);
  return std::pow(a + u * (b - a), 1.0 / p);
}

Real DiameterDistribution::mean_volume() const {
  // E[d^3] by the closed forms of the two densities.
  Real m3;
  if (grading == Grading::Uniform || d_max <= d_min) {
    m3 = d_max > d_min ? (std::pow(d_max, 4) - std::pow(d_min, 4)) / (4.0 * (d_max - d_min))
                       : std::pow(d_min, 3);
  } else {
    const Real q = fuller_exponent;
    const Real p = q - 3.0;  // exponent of the CDF; E[d^3] integrates d^(q-1)
    const Real norm = (std::abs(p) < 1e-12) ? std::log(d_max / d_min)
                                            : (std::pow(d_max, p) - std::pow(d_min, p)) / p;
    m3 = (std::pow(d_max, q) - std::pow(d_min, q)) / q / norm;
  }
  return kPi / 6.0 * m3;
}

}  // namespace rcdem
