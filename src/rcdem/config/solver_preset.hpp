#pragma once
// solver.preset (docs/model.md 6): the solver set-up a scenario file gets for the solver keys it
// leaves unset. "quasi_static", the default, is the set-up the three-point-bending study was
// tested with (SPEC 6's halving test, docs/case-study.md); "basic" is SPEC 6's plain set-up (each
// body's own step, damping 0.7, true moments of inertia). A key the file sets keeps its value.
// SolverSettings{} in code is the basic set-up: the preset is a property of scenario files.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rcdem/config/schema.hpp"

namespace rcdem::config {

inline constexpr const char* kSolverPresetKey = "solver.preset";

// The presets' names, the default first.
const std::vector<std::string>& solver_preset_names();

// The value preset `name` gives `key` ("solver.damping"), where that value does not depend on
// other keys; none for a key the preset leaves alone or for solver.dt_safety.
std::optional<Value> solver_preset_value(const std::string& name, const std::string& key);

// The preset's dt_safety for the time-step estimate in use ("per_body", "assembled"): each
// estimate has its own limit (SPEC 6), so the preset's value follows the estimate.
double solver_preset_dt_safety(const std::string& name, const std::string& estimate);

// Sets in `values` every key the preset governs that `values` lacks (solver.preset itself
// included) and returns those keys, so that messages can name the preset as their origin.
std::vector<std::string> fill_solver_preset(std::map<std::string, Value>& values);

}  // namespace rcdem::config
