#include "rcdem/config/solver_preset.hpp"

#include <utility>

namespace rcdem::config {

namespace {

struct Preset {
  std::string name;
  std::vector<std::pair<std::string, Value>> values;
  double dt_safety_assembled;
  double dt_safety_per_body;
};

// The study's values and why each: docs/case-study.md and docs/model.md 6.
const std::vector<Preset>& presets() {
  static const std::vector<Preset> all{
      {"quasi_static",
       {{"solver.time_step_estimate", std::string("assembled")},
        {"solver.damping", 0.3},
        {"solver.particle_rotational_inertia_scaling", 2.5},
        {"solver.bar_rotational_inertia_scaling", 30.0}},
       0.7,
       0.3},
      {"basic",
       {{"solver.time_step_estimate", std::string("per_body")},
        {"solver.damping", 0.7},
        {"solver.particle_rotational_inertia_scaling", 1.0},
        {"solver.bar_rotational_inertia_scaling", 1.0}},
       0.3,
       0.3},
  };
  return all;
}

const Preset& preset(const std::string& name) {
  for (const auto& p : presets())
    if (p.name == name) return p;
  return presets().front();  // the schema has checked the name
}

}  // namespace

const std::vector<std::string>& solver_preset_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& p : presets()) n.push_back(p.name);
    return n;
  }();
  return names;
}

std::optional<Value> solver_preset_value(const std::string& name, const std::string& key) {
  for (const auto& [k, v] : preset(name).values)
    if (k == key) return v;
  return std::nullopt;
}

double solver_preset_dt_safety(const std::string& name, const std::string& estimate) {
  const Preset& p = preset(name);
  return estimate == "assembled" ? p.dt_safety_assembled : p.dt_safety_per_body;
}

std::vector<std::string> fill_solver_preset(std::map<std::string, Value>& values) {
  std::vector<std::string> filled;
  if (!values.count(kSolverPresetKey)) {
    values[kSolverPresetKey] = solver_preset_names().front();
    filled.push_back(kSolverPresetKey);
  }
  const std::string name = std::get<std::string>(values.at(kSolverPresetKey));
  for (const auto& [key, value] : preset(name).values)
    if (!values.count(key)) {
      values[key] = value;
      filled.push_back(key);
    }
  if (!values.count("solver.dt_safety")) {
    const auto& estimate = std::get<std::string>(values.at("solver.time_step_estimate"));
    values["solver.dt_safety"] = solver_preset_dt_safety(name, estimate);
    filled.push_back("solver.dt_safety");
  }
  return filled;
}

}  // namespace rcdem::config
