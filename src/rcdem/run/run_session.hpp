#pragma once
// The bookkeeping around one session of a run (docs/checkpoint.md): the directory's lock, the
// signal handlers, and manifest.json, started (or, resuming, continued) before anything else can
// fail, with the scenario's inputs and their hashes; a failure is recorded in it once the run has
// started, while a run refused during its set-up leaves nothing behind.
#include <chrono>
#include <filesystem>
#include <string>

#include "rcdem/run/run.hpp"
#include "rcdem/run/run_manifest.hpp"
#include "rcdem/run/run_signals.hpp"

namespace rcdem {

class RunSession {
 public:
  RunSession(const Scenario& sc, const std::filesystem::path& out, const RunOptions& opt);
  RunSession(const RunSession&) = delete;
  RunSession& operator=(const RunSession&) = delete;

  // Checkpoints are written in this session (periodic, on signals, or resuming).
  bool checkpoints() const { return checkpoints_; }
  std::chrono::steady_clock::time_point wall_start() const { return wall_start_; }
  io::Manifest& manifest() { return manifest_; }
  const io::Inputs& inputs() const { return inputs_; }
  SignalGuard& signals() { return signals_; }

  // The set-up has passed every check: the manifest is written, and failures recorded from now.
  void started();
  // exit_state "failed" with the message, once the run has started (a resumed one always has).
  void record_failure(const std::string& what);
  // Marks the run and this session as ended in `state` ("finished", "interrupted", ...) with the
  // end time; returns this session's entry for what else it records. The caller writes.
  nlohmann::ordered_json& end(const std::string& state);

 private:
  std::filesystem::path scenario_file(const Scenario& sc);
  void check_inputs_unchanged();
  void fill_manifest(const Scenario& sc);

  const std::filesystem::path out_;
  const RunOptions& opt_;
  const std::chrono::steady_clock::time_point wall_start_;
  const bool checkpoints_;
  io::RunLock lock_;
  SignalGuard signals_;
  io::Manifest manifest_;
  std::filesystem::path scenario_file_;
  io::Inputs inputs_;
  bool manifest_started_;
};

}  // namespace rcdem
