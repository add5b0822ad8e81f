#pragma once
// The strengths' part of the calibration search (docs/model.md 7, docs/calibration.md): sigma_c
// and sigma_t as functions of tau and one tension lever (G_f,n by default, or sigma_n,t),
// linearised in logarithms,
//   y = (ln sigma_c, ln sigma_t),  x = (ln tau, ln lever),  y(x + dx) ~ y(x) + J dx,
// and solved for the target by Broyden's secant method: J starts from a prior and after every
// iteration takes the rank-one correction that makes it reproduce the step just observed
// (Broyden 1965, "good" update). The prior is the slope measured near Table 1 on the calibration
// cubes (docs/calibration.md): both strengths follow tau, and at a fixed G_f,n sigma_t *falls* as
// sigma_n,t rises (stronger contacts soften over a shorter opening relative to their elastic one,
// 2 G_f,n / sigma_n,t against sigma_n,t d / E_bar, and fail more brittly). The proportional guess
// the search used before (identity: sigma_c follows tau, sigma_t follows sigma_n,t) walked away
// from sigma_t's target there.
#include <Eigen/Dense>

#include "rcdem/core/types.hpp"

namespace rcdem {

class StrengthSecant {
 public:
  // d ln(sigma_c, sigma_t) / d ln(tau, sigma_nt) measured on the 80 mm cube near the calibrated
  // set (search iterations 2-5 of docs/calibration.md, solved for the two columns).
  static Eigen::Matrix2d measured_prior() {
    Eigen::Matrix2d j;
    j << 0.90, -0.09, 0.86, -0.35;
    return j;
  }
  // d ln(sigma_c, sigma_t) / d ln(tau, G_fn): the tau column as above; the G_f,n column measured
  // on the 160 mm cube at the calibrated set (docs/calibration.md: G_f,n x 0.823 gave sigma_t
  // x 0.930 and sigma_c x 0.987). A cube fails in tension by a crack whose load follows the
  // contacts' stiffness and fracture energy (like sqrt(E G_f)), hardly their strength: on the
  // 160 mm cube sigma_t stayed at 4.39-4.45 MPa for sigma_n,t from 2.8 to 4.2 MPa.
  static Eigen::Matrix2d fracture_energy_prior() {
    Eigen::Matrix2d j;
    j << 0.90, 0.067, 0.86, 0.37;
    return j;
  }
  explicit StrengthSecant(const Eigen::Matrix2d& prior = measured_prior())
      : prior_(prior), j_(prior) {}

  // Each step changes a strength by at most this factor (or its inverse).
  static constexpr Real kMaxFactor = 1.25;

  // The next (tau, lever) from the present ones, their measured strengths and the targets.
  // Records the pair, so that the next call corrects J with the step between them.
  Eigen::Vector2d step(const Eigen::Vector2d& tau_lever, const Eigen::Vector2d& measured,
                       const Eigen::Vector2d& target);

  // d ln(sigma_c, sigma_t) / d ln(tau, lever) as learnt so far.
  const Eigen::Matrix2d& jacobian() const { return j_; }

 private:
  Eigen::Matrix2d prior_, j_;
  bool has_previous_ = false;
  Eigen::Vector2d x_previous_ = Eigen::Vector2d::Zero(), y_previous_ = Eigen::Vector2d::Zero();
};

}  // namespace rcdem
