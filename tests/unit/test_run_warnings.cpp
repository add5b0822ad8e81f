// Warnings for legal but suspicious runs (issue 28): each fires on its condition and not just
// below it; the expectation follows the control's strength and area.
#include <gtest/gtest.h>

#include <filesystem>

#include "rcdem/config/scenario.hpp"
#include "rcdem/run/run_warnings.hpp"

namespace rcdem {
namespace {

RunOutcome sound() {
  RunOutcome o;
  o.expected_load = 1000.0;
  o.loaded_travel = 1e-5;
  o.control_travel = 2e-5;
  o.peak_load = 50.0;
  o.balance_error = 1e-5;
  return o;
}

TEST(RunWarnings, NoneForASoundRun) { EXPECT_TRUE(suspicious_run_warnings(sound()).empty()); }

TEST(RunWarnings, ALoadThatNeverRose) {
  RunOutcome o = sound();
  o.peak_load = 0.99 * kSmallLoadFraction * o.expected_load;
  ASSERT_EQ(suspicious_run_warnings(o).size(), 1u);
  EXPECT_NE(suspicious_run_warnings(o)[0].find("never rose"), std::string::npos);
  o.peak_load = 1.01 * kSmallLoadFraction * o.expected_load;
  EXPECT_TRUE(suspicious_run_warnings(o).empty());
  o.peak_load = 0.0;
  o.control_travel = 0.99 * o.loaded_travel;  // too early to tell
  EXPECT_TRUE(suspicious_run_warnings(o).empty());
  o.expected_load = 0.0;  // no control, no expectation
  o.control_travel = 1.0;
  EXPECT_TRUE(suspicious_run_warnings(o).empty());
}

TEST(RunWarnings, AnEnergyBalanceOff) {
  RunOutcome o = sound();
  o.balance_error = 1.01 * kLargeBalanceError;
  ASSERT_EQ(suspicious_run_warnings(o).size(), 1u);
  EXPECT_NE(suspicious_run_warnings(o)[0].find("energy balance"), std::string::npos);
  o.balance_error = std::nan("");
  EXPECT_EQ(suspicious_run_warnings(o).size(), 1u);
  o.balance_error = 0.99 * kLargeBalanceError;
  EXPECT_TRUE(suspicious_run_warnings(o).empty());
}

TEST(RunWarnings, ExpectationOfTheControlPlate) {
  const Scenario s =
      load_scenario(std::filesystem::path(RCDEM_SOURCE_DIR) / "tests/regression/small_run.toml");
  RunOutcome o;
  set_expectation(s, o);
  // The top plate covers the whole 50 mm face; SPEC's default sigma_n,t and E-bar.
  EXPECT_DOUBLE_EQ(o.expected_load, s.contact.sigma_nt * 0.05 * 0.05);
  EXPECT_DOUBLE_EQ(o.loaded_travel, 10.0 * s.contact.sigma_nt / s.contact.E_bar * 0.05);
}

}  // namespace
}  // namespace rcdem
