#include <gtest/gtest.h>

#include <sstream>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/schema.hpp"
#include "rcdem/core/error.hpp"
#include "small_scenarios.hpp"

using namespace rcdem;

namespace {

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "bad.toml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Scenario, DefaultsAreTable2) {
  const Scenario s = test::small_box();
  EXPECT_DOUBLE_EQ(s.contact.E_bar, 48.7e9);
  EXPECT_DOUBLE_EQ(s.contact.alpha, 0.3);
  EXPECT_DOUBLE_EQ(s.contact.sigma_nt, 4.15e6);
  EXPECT_DOUBLE_EQ(s.contact.G_fs, 2380.785);
  EXPECT_DOUBLE_EQ(s.generation.aggregate_content, 568.5);
  EXPECT_DOUBLE_EQ(s.generation.porosity, 0.10);
  EXPECT_EQ(s.specimen.size, Vec3(0.06, 0.05, 0.04));
}

TEST(Scenario, UnknownKeyNamesFileLineAndKnownKeys) {
  const std::string msg = error_of("[specimen]\nshape = \"box\"\nsize = [0.1,0.1,0.1]\nsiz = 3\n");
  EXPECT_NE(msg.find("bad.toml:4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown key 'specimen.siz'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("size"), std::string::npos) << msg;
}

TEST(Scenario, WrongTypeAndRangeSayWhatWasExpected) {
  std::string msg = error_of(test::small_box_text(1, "voronoi", "[contact]\nalpha = \"x\"\n"));
  EXPECT_NE(msg.find("contact.alpha"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a number"), std::string::npos) << msg;
  msg = error_of(test::small_box_text(1, "voronoi", "[contact]\nE_bar = -1.0\n"));
  EXPECT_NE(msg.find("in [1000, 1e+13]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("got -1"), std::string::npos) << msg;
}

TEST(Scenario, MissingRequiredKey) {
  const std::string msg = error_of("[specimen]\nshape = \"box\"\n");
  EXPECT_NE(msg.find("missing required key 'specimen.size'"), std::string::npos) << msg;
}

TEST(Scenario, CrossKeyChecks) {
  EXPECT_NE(error_of(test::small_box_text(1, "voronoi", "[generation.aggregate]\nd_min = 0.013\n"))
                .find("must not exceed"),
            std::string::npos);
  EXPECT_NE(
      error_of(test::small_box_text(1, "voronoi", "[generation.aggregate]\ncontent = 2500.0\n"))
          .find("cannot fit"),
      std::string::npos);
}

TEST(Schema, TemplateParsesBackWithEveryDefault) {
  // print-schema's template, with the required keys filled in, is itself a valid scenario.
  std::ostringstream out;
  config::scenario_schema().print_template(out);
  std::string text = out.str();
  const auto fill = [&](const std::string& from, const std::string& to) {
    const auto pos = text.find(from);
    ASSERT_NE(pos, std::string::npos);
    text.replace(pos, from.size(), to);
  };
  fill("# shape = ...   # required", "shape = \"box\"");
  fill("# size = ...   # required", "size = [0.1, 0.1, 0.1]");
  const Scenario s = parse_scenario(text, "template.toml");
  EXPECT_EQ(s.generation.relaxation_iterations, 300);
  EXPECT_DOUBLE_EQ(s.contact.G_fn, 9.002);
}
