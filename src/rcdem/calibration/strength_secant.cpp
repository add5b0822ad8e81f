#include "rcdem/calibration/strength_secant.hpp"

#include <algorithm>
#include <cmath>

namespace rcdem {

Eigen::Vector2d StrengthSecant::step(const Eigen::Vector2d& tau_lever,
                                     const Eigen::Vector2d& measured,
                                     const Eigen::Vector2d& target) {
  const Eigen::Vector2d x = tau_lever.array().log();
  const Eigen::Vector2d y = measured.array().log();
  if (has_previous_) {
    const Eigen::Vector2d dx = x - x_previous_, dy = y - y_previous_;
    // A step too small to measure a slope (the other parameters moved alone) teaches nothing.
    if (dx.norm() > 1e-4) j_ += (dy - j_ * dx) * dx.transpose() / dx.squaredNorm();
  }
  x_previous_ = x;
  y_previous_ = y;
  has_previous_ = true;
  const Eigen::Vector2d misfit = target.array().log() - y.array();
  // A secant that has lost its rank (|det J| small against its entries) falls back to the prior
  // for this step, and is rebuilt from it.
  const Real scale = j_.cwiseAbs().maxCoeff();
  if (std::abs(j_.determinant()) < 1e-3 * scale * scale) j_ = prior_;
  Eigen::Vector2d dx = j_.partialPivLu().solve(misfit);
  const Real limit = std::log(kMaxFactor);
  for (int k = 0; k < 2; ++k) dx[k] = std::clamp(dx[k], -limit, limit);
  return (x + dx).array().exp();
}

}  // namespace rcdem
