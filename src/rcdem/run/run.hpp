#pragma once
// A whole run (SPEC 6, 11): specimen, solver, stop rules, history, snapshots, summary; and, for
// production runs (issue 6), checkpoints, resuming, signals and the run manifest.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "rcdem/config/scenario.hpp"
#include "rcdem/solver/simulation.hpp"

namespace rcdem {

class RankGroup;

struct RunSummary {
  std::string stop_reason;  // a stop rule, or "interrupted" (a signal; see `signal`)
  int signal = 0;           // SIGINT or SIGTERM when interrupted
  Real peak_load = 0.0;
  Real displacement_at_peak = 0.0;
  Real kinetic_over_strain_at_peak = 0.0;
  std::int64_t steps = 0;
  Real time = 0.0;
  Energy energy;
  nlohmann::ordered_json json;
  std::vector<std::string> history_columns;
  std::vector<std::vector<double>> history_rows;
  std::filesystem::path checkpoint;  // the last checkpoint written, if any
};

// What a caller's hook decides after a step (RunOptions::decide).
enum class RunDecision {
  Continue,
  Stop,       // the run ends as if a stop rule had triggered (stop_reason "callback")
  Until,      // the same, the caller's end reached (stop_reason "until")
  Interrupt,  // as a signal does: a checkpoint, outputs so far, resumable with --resume
};

// How a run is kept safe (docs/checkpoint.md). The defaults are those of library callers
// (calibration, the study's in-process runs): a manifest, no checkpoint, signals untouched.
// `rcdem run` checkpoints every 10 minutes of wall time and on SIGINT/SIGTERM.
struct RunOptions {
  // Continue the run in `out` from its newest usable checkpoint (the scenario must be the one it
  // started with: run_directory_scenario()). Appends to its history and manifest.
  bool resume = false;
  // Periodic checkpoints: every this many steps, and/or this many seconds of wall time (0: no).
  std::int64_t checkpoint_every_steps = 0;
  double checkpoint_every_seconds = 0.0;
  // The interval as the user gave it ("5000", "10min"), recorded in the manifest so that a
  // --resume without --checkpoint-every keeps it (empty: not recorded).
  std::string checkpoint_every_text;
  // SIGINT/SIGTERM during the loop: finish the step, write a checkpoint, history.csv and
  // broken_points.csv, and return with stop_reason "interrupted". A second signal a second or
  // more after the first kills at once (run_signals.cpp).
  bool handle_signals = false;
  // Once the run has finished and written its results, its checkpoints are removed.
  bool keep_checkpoints = false;
  // manifest.json in `out` (docs/checkpoint.md).
  bool manifest = true;
  // The caller holds `out`'s run.lock (io::OutputDirectory), so the run takes none of its own.
  bool lock_held = false;
  // Called once the set-up has passed every check and the run's first files are written: the
  // run has started cleanly (io::OutputDirectory::commit).
  std::function<void()> on_started;
  std::vector<std::string> command;  // the command line, for the manifest
  // Called every `decide_every` steps, after the step's outputs and stop rules, with the
  // simulation, which it may change (a plate's velocity); Python's run callback. A run with one
  // may be interrupted by it, so it keeps the directory's lock as a checkpointing run does.
  std::function<RunDecision(Simulation&)> decide;
  std::int64_t decide_every = 1;
  // Threads (--threads): 0 follows the free cores during the loop, up to the OpenMP runtime's
  // count (core/thread_count_tuner.hpp); N > 0 runs exactly N, the specimen's generation included.
  int threads = 0;
  // Rank 0 of a distributed run (run/distributed_run.hpp): the simulation is distributed over the
  // group's ranks, which build it with this one and follow its steps.
  RankGroup* ranks = nullptr;
};

// Checks that the scenario describes a run that can end: plates, a control plate where a rule
// needs one, a rule that can trigger. Throws rcdem::Error naming the key.
void validate_run(const Scenario& scenario);

// Runs the scenario, writing history.csv, snapshots, summary.json into `out` (which must exist).
// `on_step` (optional) is called after every step, for callers that follow the run.
RunSummary run_scenario(const Scenario& scenario, const std::filesystem::path& out,
                        const std::function<void(const Simulation&)>& on_step = {});
RunSummary run_scenario(const Scenario& scenario, const std::filesystem::path& out,
                        const RunOptions& options,
                        const std::function<void(const Simulation&)>& on_step = {});

// The same with a simulation the caller built from `scenario` (and may have stepped, or restored:
// with options.resume its state is replaced by the newest checkpoint's in `out`).
RunSummary run_simulation(const Scenario& scenario, Simulation& sim,
                          const std::filesystem::path& out, const RunOptions& options);

// The scenario of the run in `dir`, for --resume: DIR/scenario.toml (the scenario as run), its
// includes resolved from where the original file was (manifest.json), named as it was. Refuses a
// directory that is not a run, or whose run has finished.
Scenario run_directory_scenario(const std::filesystem::path& dir);

// A run killed after writing summary.json but before its manifest's last update: the manifest
// completed (finished, checkpoints removed, the plot drawn if missing). Returns false, touching
// nothing, for any other directory.
bool complete_finished_run(const std::filesystem::path& dir);

}  // namespace rcdem
