// A run whose state stops being finite must fail, not finish (issue 28, 6): the error names the
// step, the history written so far stays, and the manifest records the failure.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/run/run.hpp"

namespace rcdem {
namespace {

namespace fs = std::filesystem;

int count_lines(const fs::path& p) {
  std::ifstream in(p);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

TEST(RunFailures, NonFiniteStateStopsTheRunAndKeepsTheHistory) {
  Scenario s = load_scenario(fs::path(RCDEM_SOURCE_DIR) / "tests/regression/small_run.toml");
  // Past the schema, which refuses it: k_s = 0, and the BL law's shear limit divides by k_s, so
  // the dissipated energy is NaN from the first step on while every body stays finite. Before
  // the check the run finished with exit 0 and a NaN energy balance.
  s.contact.alpha = 0.0;
  s.output.history_rows = 3000;  // a row per step
  const fs::path out = fs::temp_directory_path() / "rcdem_run_failures_test";
  fs::remove_all(out);
  fs::create_directories(out);
  Progress::set_quiet_default(true);
  std::string message;
  try {
    run_scenario(s, out);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_EQ(message.find("small_run.toml: non-finite state at step 1 "), message.find("small_run"))
      << message;
  EXPECT_NE(message.find("non-finite state at step 1 "), std::string::npos) << message;
  EXPECT_NE(message.find("nan J; no body"), std::string::npos) << message;
  EXPECT_NE(message.find("history.csv is kept, up to step 0)"), std::string::npos) << message;
  EXPECT_EQ(count_lines(out / "history.csv"), 2);  // the header and step 0
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  std::ifstream manifest(out / "manifest.json");
  const std::string text((std::istreambuf_iterator<char>(manifest)), {});
  EXPECT_NE(text.find("\"exit_state\": \"failed\""), std::string::npos);
  fs::remove_all(out);
}

}  // namespace
}  // namespace rcdem
