#pragma once
// Small scenarios shared by the tests: a few hundred particles, generated in well under a second.
#include <fmt/format.h>

#include <string>

#include "rcdem/config/scenario.hpp"

namespace rcdem::test {

inline std::string small_box_text(int seed = 1, const std::string& tessellation = "voronoi",
                                  const std::string& extra = "") {
  return fmt::format(R"(
[specimen]
shape = "box"
size = [0.06, 0.05, 0.04]
[generation]
seed = {}
relaxation_iterations = 100
[tessellation]
kind = "{}"
{}
)",
                     seed, tessellation, extra);
}

inline Scenario small_box(int seed = 1, const std::string& tessellation = "voronoi") {
  return parse_scenario(small_box_text(seed, tessellation), "small_box.toml");
}

}  // namespace rcdem::test
