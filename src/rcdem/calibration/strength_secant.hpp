#pragma once
// The strengths' part of the calibration search (docs/model.md 7, docs/calibration.md): sigma_c
// and sigma_t as functions of the contact strengths tau and sigma_n,t, linearised in logarithms,
//   y = (ln sigma_c, ln sigma_t),  x = (ln tau, ln sigma_n,t),  y(x + dx) ~ y(x) + J dx,
// and solved for the target by Broyden's secant method: J starts as the identity (sigma_c follows
// tau, sigma_t follows sigma_n,t, in proportion: the update the search used alone before), and
// after every iteration takes the rank-one correction that makes it reproduce the step just
// observed (Broyden 1965, "good" update). The diagonal guess fails where sigma_t rises as
// sigma_n,t falls (a fixed G_f,n makes weaker contacts relatively more ductile); the secant learns
// that sign from the first step that shows it.
#include <Eigen/Dense>

#include "rcdem/core/types.hpp"

namespace rcdem {

class StrengthSecant {
 public:
  // Each step changes a strength by at most this factor (or its inverse).
  static constexpr Real kMaxFactor = 1.25;

  // The next (tau, sigma_nt) from the present ones, their measured strengths and the targets.
  // Records the pair, so that the next call corrects J with the step between them.
  Eigen::Vector2d step(const Eigen::Vector2d& tau_sigma_nt, const Eigen::Vector2d& measured,
                       const Eigen::Vector2d& target);

  // d ln(sigma_c, sigma_t) / d ln(tau, sigma_nt) as learnt so far.
  const Eigen::Matrix2d& jacobian() const { return j_; }

 private:
  Eigen::Matrix2d j_ = Eigen::Matrix2d::Identity();
  bool has_previous_ = false;
  Eigen::Vector2d x_previous_ = Eigen::Vector2d::Zero(), y_previous_ = Eigen::Vector2d::Zero();
};

}  // namespace rcdem
