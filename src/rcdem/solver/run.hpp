#pragma once
// A whole run (SPEC 6, 11): specimen, solver, stop rules, history, snapshots, summary.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "rcdem/io/scenario.hpp"
#include "rcdem/solver/simulation.hpp"

namespace rcdem {

struct RunSummary {
  std::string stop_reason;
  Real peak_load = 0.0;
  Real displacement_at_peak = 0.0;
  Real kinetic_over_strain_at_peak = 0.0;
  std::int64_t steps = 0;
  Real time = 0.0;
  Energy energy;
  nlohmann::ordered_json json;
  std::vector<std::string> history_columns;
  std::vector<std::vector<double>> history_rows;
};

// Checks that the scenario describes a run that can end: plates, a control plate where a rule
// needs one, a rule that can trigger. Throws rcdem::Error naming the key.
void validate_run(const Scenario& scenario);

// Runs the scenario, writing history.csv, snapshots, summary.json into `out` (which must exist).
// `on_step` (optional) is called after every step, for callers that follow the run.
RunSummary run_scenario(const Scenario& scenario, const std::filesystem::path& out,
                        const std::function<void(const Simulation&)>& on_step = {});

}  // namespace rcdem
