#pragma once
// What a study checks of a case it finds finished before trusting it: that it ran the scenario the
// study would run now (the hash of its inputs in manifest.json), and that the files its tables
// and report read have the shape rcdem writes (summary.json's fields and types, history.csv's
// rows complete up to the run's last step).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "rcdem/config/scenario.hpp"

namespace rcdem {

struct FinishedCase {
  enum class State { finished, scenario_changed, damaged };
  State state = State::damaged;
  std::string why;          // for scenario_changed and damaged: what, naming the file
  nlohmann::json summary;   // for finished: the case's summary.json
};

// Checks the run directory `dir`, which holds a summary.json, against `scenario`.
FinishedCase check_finished_case(const std::filesystem::path& dir, const Scenario& scenario);

// summary.json of a run: parsed and with every field a study reads, of the right type; throws
// Error naming the file and the field otherwise.
nlohmann::json read_run_summary(const std::filesystem::path& file);

}  // namespace rcdem
