// The nesting scan that runs before the TOML parser: it must pass every legal text whatever its
// strings and comments hold, and refuse deep nesting with the line it starts on.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/scenario_text.hpp"
#include "rcdem/core/error.hpp"

namespace rcdem::config {
namespace {

std::string dotted(int levels) {
  std::string key = "a";
  for (int i = 1; i < levels; ++i) key += ".a";
  return key;
}

std::string message_of(const std::string& text) {
  try {
    check_scenario_nesting(text, "t.toml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioText, PassesBracketsDotsAndQuotesInsideStringsAndComments) {
  const std::string deep_brackets(40, '[');
  const std::string deep_dots = dotted(40);
  const std::string text = "# a comment with " + deep_brackets + " and " + deep_dots +
                           "\n"
                           "a = \"" +
                           deep_brackets + deep_dots +
                           " \\\" still the string\"\n"
                           "b = '" +
                           deep_brackets +
                           "'\n"
                           "c = \"\"\"\n" +
                           deep_brackets +
                           "\n\"\" \"\"\"\n"
                           "d = '''" +
                           deep_brackets + "\n" + deep_dots +
                           "'''\n"
                           "\"" +
                           deep_dots +
                           "\".x = 1  # one quoted segment, then one more\n"
                           "e = [[1.5, 2.5], [3.25e-3]]\n"
                           "f = { g.h = 1.5, i = [0.1, 0.2] }\n"
                           "[bars.\"" +
                           deep_dots +
                           "\"]\n"
                           "[[tables.of.arrays]]\n";
  EXPECT_EQ(message_of(text), "");
}

TEST(ScenarioText, PassesTheLimitAndRefusesOneLevelMore) {
  EXPECT_EQ(message_of(dotted(kMaxKeyDepth) + " = 1\n"), "");
  EXPECT_EQ(message_of("[" + dotted(kMaxKeyDepth) + "]\n"), "");
  const std::string value_ok = std::string(kMaxValueDepth, '[') + std::string(kMaxValueDepth, ']');
  EXPECT_EQ(message_of("x = " + value_ok + "\n"), "");

  EXPECT_NE(message_of("\n\n" + dotted(kMaxKeyDepth + 1) + " = 1\n").find("t.toml:3: a key"),
            std::string::npos);
  EXPECT_NE(message_of("[" + dotted(kMaxKeyDepth + 1) + "]\n").find("t.toml:1: a key"),
            std::string::npos);
  EXPECT_NE(message_of("x = { " + dotted(kMaxKeyDepth + 1) + " = 1 }\n").find("nested more"),
            std::string::npos);
  const std::string arrays = std::string(kMaxValueDepth + 1, '[');
  EXPECT_NE(message_of("x = 1\ny = " + arrays + "\n").find("t.toml:2: arrays"), std::string::npos);
  std::string inline_tables = "x = ";
  for (int i = 0; i <= kMaxValueDepth; ++i) inline_tables += "{ a = ";
  EXPECT_NE(message_of(inline_tables + "\n").find("inline tables"), std::string::npos);
}

TEST(ScenarioText, ArraysOverSeveralLinesKeepTheirDepth) {
  // A key-like line inside an open array is a value, not a key: its dots do not count.
  EXPECT_EQ(message_of("x = [\n  " + dotted(40) + ",\n]\n"), "");
  std::string lines = "x = ";
  for (int i = 0; i <= kMaxValueDepth; ++i) lines += "[\n";
  EXPECT_NE(message_of(lines).find("arrays or inline tables"), std::string::npos);
}

TEST(ScenarioText, ReadsOnlyRegularFilesBelowTheCap) {
  const auto dir = std::filesystem::temp_directory_path() / "rcdem_scenario_text_test";
  std::filesystem::create_directories(dir);
  const auto ok = dir / "ok.toml";
  std::ofstream(ok) << "a = 1\n";
  EXPECT_EQ(read_scenario_file(ok, "scenario"), "a = 1\n");
  EXPECT_THROW(read_scenario_file(dir, "include", "x.toml:1: key 'include'"), Error);
  EXPECT_THROW(read_scenario_file(dir / "missing.toml", "scenario"), Error);
  EXPECT_THROW(read_scenario_file("/dev/zero", "include"), Error);
  const auto big = dir / "big.toml";
  std::ofstream(big) << std::string(kMaxScenarioBytes + 1, '#');
  try {
    read_scenario_file(big, "include", "x.toml:1: key 'include'");
    ADD_FAILURE() << "an oversized file was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("x.toml:1: key 'include': cannot read include"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rcdem::config

namespace rcdem {
namespace {

// Every scenario shipped (examples, golden cases, regression inputs) passes the guards and the
// loader: the limits above refuse nothing a user was given.
TEST(ScenarioText, EveryShippedScenarioLoads) {
  const std::filesystem::path root(RCDEM_SOURCE_DIR);
  int loaded = 0;
  for (const char* dir : {"examples", "tests/golden/scenarios", "tests/regression"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(root / dir)) {
      const auto name = e.path().filename();
      if (e.path().extension() != ".toml" || name == "calibrated_contact.toml" ||
          name == "calibrated_contact_quick.toml")
        continue;  // the fragments: included by others, not scenarios of their own
      EXPECT_NO_THROW(load_scenario(e.path())) << e.path();
      ++loaded;
    }
  EXPECT_GE(loaded, 70);
}

}  // namespace
}  // namespace rcdem
