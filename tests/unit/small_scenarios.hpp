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

// A 40 mm box pulled apart between glued plates at `velocity` [m/s]: it peaks near step 1,500 and
// cracks through in a few thousand steps. `law`: contact.law; `solver`: more [solver] lines.
inline Scenario pulled_box(const std::string& law = "BL", const std::string& solver = "",
                           double velocity = 0.05) {
  return parse_scenario(fmt::format(R"(
[specimen]
shape = "box"
size = [0.04, 0.04, 0.04]
[generation]
seed = 2
relaxation_iterations = 100
[contact]
law = "{}"
[solver]
preset = "basic"
{}
[plates.bottom]
face = "z-"
glued = true
[plates.top]
face = "z+"
glued = true
velocity = {}
ramp_time = 2.0e-5
[loading]
control_plate = "top"
)",
                                    law, solver, velocity),
                        "pulled_box.toml");
}

}  // namespace rcdem::test
