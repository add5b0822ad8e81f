// `--set KEY=VALUE`, `rcdem run --seed` and a study's `--seeds`: the scenario's text with keys set
// and every other byte kept, wherever the file sets (or does not set) them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/scenario_overrides.hpp"
#include "rcdem/core/error.hpp"

namespace rcdem::config {
namespace {

const char* const kBox = "[specimen]\nshape = \"box\"\nsize = [0.05, 0.05, 0.05]\n";

std::string message_of(const std::string& text) {
  try {
    with_generation_seed(text, "t.toml", 5);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioSeed, ReplacesTheValueAndKeepsEveryOtherByte) {
  const std::string text = std::string(kBox) +
                           "# the packing\n[generation]  # header comment\nseed   =  12 # why 12\n"
                           "porosity = 0.1\n";
  const std::string got = with_generation_seed(text, "t.toml", 7);
  EXPECT_EQ(got, std::string(kBox) +
                     "# the packing\n[generation]  # header comment\nseed   =  7 # why 12\n"
                     "porosity = 0.1\n");
  EXPECT_EQ(parse_scenario(got, "t.toml").generation.seed, 7u);
  // The same seed gives the same text, so a study's seed 1 of a seed-1 scenario runs the file.
  EXPECT_EQ(with_generation_seed(text, "t.toml", 12), text);
}

TEST(ScenarioSeed, AddsTheKeyUnderItsHeaderOrAppendsTheTable) {
  const std::string header = std::string(kBox) + "[generation]\nporosity = 0.1\n[output]\n";
  EXPECT_EQ(with_generation_seed(header, "t.toml", 3),
            std::string(kBox) + "[generation]\nseed = 3\nporosity = 0.1\n[output]\n");
  const std::string none = kBox;
  const std::string appended = with_generation_seed(none, "t.toml", 9000000000000000);
  EXPECT_EQ(appended, none + "\n[generation]\nseed = 9000000000000000\n");
  EXPECT_EQ(parse_scenario(appended, "t.toml").generation.seed, 9000000000000000u);
  // Only a sub-table: TOML lets [generation] follow [generation.aggregate].
  const std::string sub = std::string(kBox) + "[generation.aggregate]\nd_max = 0.012\n";
  const Scenario s = parse_scenario(with_generation_seed(sub, "t.toml", 4), "t.toml");
  EXPECT_EQ(s.generation.seed, 4u);
  EXPECT_EQ(s.generation.aggregate_d_max, 0.012);
  // A seed in an inline table or a dotted key on one line is a value like any other.
  EXPECT_EQ(with_generation_seed("generation = { seed = 1, porosity = 0.1 }\n", "t.toml", 22),
            "generation = { seed = 22, porosity = 0.1 }\n");
  EXPECT_EQ(with_generation_seed("generation.seed = 1\n", "t.toml", 22), "generation.seed = 22\n");
}

TEST(ScenarioSeed, OverridesAnIncludedFragmentsSeed) {
  const auto dir = std::filesystem::temp_directory_path() / "rcdem_scenario_seed_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "fragment.toml") << "[generation]\nseed = 1\n";
  const std::string text = std::string("include = [\"fragment.toml\"]\n") + kBox;
  const std::string main = (dir / "main.toml").string();
  EXPECT_EQ(parse_scenario(text, main).generation.seed, 1u);
  EXPECT_EQ(parse_scenario(with_generation_seed(text, main, 6), main).generation.seed, 6u);
  std::filesystem::remove_all(dir);
}

TEST(ScenarioSeed, RefusesWhatItCannotEditNamingTheFile) {
  // Dotted keys without a seed, or an inline table without one: appending [generation] would
  // redefine the table.
  for (const char* text : {"generation.porosity = 0.1\n", "generation = { porosity = 0.1 }\n",
                           "generation = 3\n", "[generation\n"}) {
    const std::string m = message_of(text);
    EXPECT_NE(m.find("t.toml"), std::string::npos) << text << " -> " << m;
  }
  EXPECT_NE(message_of("generation.porosity = 0.1\n").find("set it in the file"),
            std::string::npos);
}

Override one(const std::string& item) { return parse_overrides({item}).front(); }

std::string override_error(const std::vector<std::string>& items) {
  try {
    for (const auto& o : parse_overrides(items)) check_override(o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioOverride, WritesTheValueWhereTheFileSetsIt) {
  const std::string text = std::string(kBox) + "# damping\n[solver]\ndamping = 0.2  # why\n";
  EXPECT_EQ(with_override(text, "t.toml", one("solver.damping=0.3")),
            std::string(kBox) + "# damping\n[solver]\ndamping = 0.3  # why\n");
  // Under its section's header when the file does not set it; a section appended when it has none.
  EXPECT_EQ(with_override(text, "t.toml", one("solver.time_step=1e-7")),
            std::string(kBox) + "# damping\n[solver]\ntime_step = 1e-7\ndamping = 0.2  # why\n");
  EXPECT_EQ(with_override(kBox, "t.toml", one("stop.steps=200")),
            std::string(kBox) + "\n[stop]\nsteps = 200\n");
  // A named section's key, a string given as a bare word, an array.
  const std::string plate = std::string(kBox) + "[plates.top]\nface = \"z+\"\n";
  EXPECT_EQ(with_override(plate, "t.toml", one("plates.top.velocity=-0.1")),
            std::string(kBox) + "[plates.top]\nvelocity = -0.1\nface = \"z+\"\n");
  EXPECT_EQ(with_override(kBox, "t.toml", one("specimen.shape=beam")),
            "[specimen]\nshape = \"beam\"\nsize = [0.05, 0.05, 0.05]\n");
  EXPECT_EQ(with_override(kBox, "t.toml", one("specimen.size=[0.1, 0.1, 0.1]")),
            "[specimen]\nshape = \"box\"\nsize = [0.1, 0.1, 0.1]\n");
}

TEST(ScenarioOverride, TheScenarioReadIsTheOneWithTheValue) {
  const std::string text = with_override(kBox, "t.toml", one("solver.damping=0.25"));
  EXPECT_EQ(parse_scenario(text, "t.toml").solver.damping, 0.25);
}

TEST(ScenarioOverride, ErrorsNameTheCommandLine) {
  EXPECT_EQ(override_error({"solver.damping=abc"}),
            "--set 'solver.damping=abc': key 'solver.damping': expected a number in [0, 1), got "
            "\"abc\"");
  EXPECT_EQ(override_error({"solver.damping=2"}).rfind("--set 'solver.damping=2': key", 0), 0u);
  EXPECT_NE(override_error({"solver.dampin=0.3"}).find("unknown key 'solver.dampin' (known in "
                                                       "[solver]:"),
            std::string::npos);
  EXPECT_EQ(override_error({"stop.steps=1", "stop.steps=2"}), "--set: stop.steps is given twice");
  EXPECT_EQ(override_error({"=3"}).rfind("--set '=3': expected KEY=VALUE", 0), 0u);
  EXPECT_EQ(override_error({"solver=3"}).rfind("--set 'solver=3': 'solver' is a section", 0), 0u);
  EXPECT_EQ(override_error({"specimen.shape=\"unterminated"}).rfind("--set", 0), 0u);
  EXPECT_EQ(override_error({"solver.damping=0.3"}), "");
}

}  // namespace
}  // namespace rcdem::config
