#pragma once
// Warnings for a run that is legal but whose result is suspicious (issue 28): printed as
// "rcdem: warning: ..." and kept in summary.json's "warnings". Thresholds: docs/model.md 11.
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/types.hpp"

namespace rcdem {

struct RunOutcome {
  Real peak_load = 0.0;       // N
  Real expected_load = 0.0;   // N: what the control must carry once the specimen is loaded
  Real control_travel = 0.0;  // m: how far the control plate or pulled bar moved
  Real loaded_travel = 0.0;   // m: by which it must have loaded the specimen
  Real balance_error = 0.0;   // SPEC 11's |W - (E_s + E_k + D)| / max(W, ...)
};

// A peak below this fraction of the expected load, once the control has travelled far enough.
inline constexpr Real kSmallLoadFraction = 0.01;
// An energy balance error above this at the end (SPEC 11 keeps it below 1e-4 in a sound run).
inline constexpr Real kLargeBalanceError = 0.01;

// The expected load and travel of the scenario's control: a plate, the concrete's contact tensile
// strength over the plate's area once it has moved ten cracking strains of the specimen's length
// (every test of concrete carries at least that: a tension test about 1x, compression 20x,
// bending 1-2x); a pulled bar, its yield force once it has moved ten yield strains of its length.
// No control: no expectation (expected_load 0).
void set_expectation(const Scenario& sc, RunOutcome& o);

std::vector<std::string> suspicious_run_warnings(const RunOutcome& o);

}  // namespace rcdem
