// The calibration search's parameter update and target parsing (calibration/calibrate.hpp).
#include <gtest/gtest.h>

#include "rcdem/calibration/calibrate.hpp"
#include "rcdem/core/error.hpp"

using namespace rcdem;

TEST(CalibrationUpdate, MeasuredEqualToTargetIsAFixedPoint) {
  const ContactParameters p;  // Table 2
  const MacroProperties t{34.2e9, 0.15, 91.2e6, 4.0e6};
  const ContactParameters q = update_parameters(p, t, t);
  EXPECT_NEAR(q.alpha, p.alpha, 1e-12);
  EXPECT_NEAR(q.E_bar / p.E_bar, 1.0, 1e-12);
  EXPECT_NEAR(q.sigma_nt / p.sigma_nt, 1.0, 1e-12);
  EXPECT_NEAR(q.tau / p.tau, 1.0, 1e-12);
  EXPECT_EQ(q.G_fn, p.G_fn);
  EXPECT_EQ(q.mu_c, p.mu_c);
}

TEST(CalibrationUpdate, EachMisfitMovesItsParameterTheRightWay) {
  const ContactParameters p;
  const MacroProperties t{34.2e9, 0.15, 91.2e6, 4.0e6};
  // Too stiff -> softer contacts; nu too high -> more shear stiffness (nu falls with alpha);
  // too strong in tension -> lower sigma_n,t; too weak in compression -> higher tau.
  const ContactParameters q = update_parameters(p, {40.0e9, 0.18, 80.0e6, 4.4e6}, t);
  EXPECT_GT(q.alpha, p.alpha);
  EXPECT_LT(q.sigma_nt, p.sigma_nt);
  EXPECT_NEAR(q.sigma_nt / p.sigma_nt, 4.0 / 4.4, 1e-12);
  EXPECT_NEAR(q.tau / p.tau, 91.2 / 80.0, 1e-12);
  // E_bar: the measured E scaled to the target, less the stiffening that the new alpha brings.
  const auto lattice_e = [](Real a) { return (2.0 + 3.0 * a) / (4.0 + a); };
  EXPECT_NEAR(q.E_bar / p.E_bar, (34.2 / 40.0) * lattice_e(p.alpha) / lattice_e(q.alpha), 1e-12);
}

TEST(CalibrationTarget, ParsesAllFourAndRejectsTheRest) {
  const MacroProperties m = parse_macro_properties("E=34.2e9,nu=0.15,sigma_c=91.2e6,sigma_t=4.0e6");
  EXPECT_DOUBLE_EQ(m.E, 34.2e9);
  EXPECT_DOUBLE_EQ(m.nu, 0.15);
  EXPECT_DOUBLE_EQ(m.sigma_c, 91.2e6);
  EXPECT_DOUBLE_EQ(m.sigma_t, 4.0e6);
  EXPECT_THROW(parse_macro_properties("E=34.2e9,nu=0.15,sigma_c=91.2e6"), Error);
  EXPECT_THROW(parse_macro_properties("E=34.2e9,nu=0.15,sigma_c=91.2e6,sigma_t=-4"), Error);
  EXPECT_THROW(parse_macro_properties("E=34.2e9,nu=0.3,sigma_c=91.2e6,sigma_t=4e6"), Error);
  EXPECT_THROW(parse_macro_properties("E=34.2e9,nu=0.15,sigma_c=91.2e6,sigma_t=4e6,G=1"), Error);
}
