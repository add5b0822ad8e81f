#pragma once
// What a run does after each step besides stepping, as observers with triggers (in the manner of
// HOOMD-blue's Analyzer + Trigger): the peak, the history and crack record, snapshots, the
// progress line, and the stop rules. The run loop (run/run.cpp) calls each observer whose trigger
// accepts the step, in the order they were added, then asks the stop rules; adding an output is
// one new RunObserver, adding a stop rule one new StopRule in stop_rules().
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/run/crack_record.hpp"
#include "rcdem/run/run_output.hpp"
#include "rcdem/solver/simulation.hpp"

namespace rcdem {

// The state after one whole step, as the observers see it.
struct StepView {
  const Simulation& sim;
  std::int64_t step = 0;
  Real load = 0.0;          // the control's load (a plate's, or a pulled bar's)
  Real displacement = 0.0;  // the control's displacement
};

// When an observer acts: on every `period`-th step (0: never).
class Trigger {
 public:
  static Trigger every(std::int64_t period) { return Trigger(period); }
  bool operator()(std::int64_t step) const { return period_ > 0 && step % period_ == 0; }
  std::int64_t period() const { return period_; }

 private:
  explicit Trigger(std::int64_t period) : period_(period) {}
  std::int64_t period_;
};

class RunObserver {
 public:
  explicit RunObserver(Trigger trigger) : trigger_(trigger) {}
  virtual ~RunObserver() = default;
  const Trigger& trigger() const { return trigger_; }
  virtual void act(const StepView& step) = 0;

 private:
  Trigger trigger_;
};

// The largest load so far, where it was reached and how dynamic the run was there; kept in the
// loop's checkpointed state so that a resumed run continues it.
class PeakTracker final : public RunObserver {
 public:
  explicit PeakTracker(io::LoopState& state) : RunObserver(Trigger::every(1)), s_(state) {}
  void act(const StepView& step) override;
  Real peak() const { return s_.peak; }
  Real displacement_at_peak() const { return s_.displacement_at_peak; }

 private:
  io::LoopState& s_;
};

// A history row and the crack record's update.
class HistoryRecorder final : public RunObserver {
 public:
  HistoryRecorder(Trigger t, io::History& history, io::CrackRecord& cracks)
      : RunObserver(t), history_(history), cracks_(cracks) {}
  void act(const StepView& step) override;

 private:
  io::History& history_;
  io::CrackRecord& cracks_;
};

// A snapshot (VTU + PVD) and history.csv rewritten, so that a stopped run keeps both.
class SnapshotRecorder final : public RunObserver {
 public:
  SnapshotRecorder(Trigger t, io::SnapshotWriter& snapshots, const io::History& history,
                   std::filesystem::path out)
      : RunObserver(t), snapshots_(snapshots), history_(history), out_(std::move(out)) {}
  void act(const StepView& step) override;

 private:
  io::SnapshotWriter& snapshots_;
  const io::History& history_;
  std::filesystem::path out_;
};

// The progress line on stderr: every half second on a terminal, every 10 s in a log.
class ProgressLine final : public RunObserver {
 public:
  ProgressLine(Real expected_steps, const PeakTracker& peak);
  void act(const StepView& step) override;
  // Ends the line on a terminal.
  void close() const;

 private:
  Real expected_;
  const PeakTracker& peak_;
  bool tty_;
  std::int64_t first_step_ = -1;
  std::chrono::steady_clock::time_point start_, last_;
};

// A rule that ends the run after a step; `reason` goes to summary.json's stop_reason.
class StopRule {
 public:
  virtual ~StopRule() = default;
  virtual const char* reason() const = 0;
  virtual bool triggered(const StepView& step) const = 0;
};

// The scenario's active stop rules (SPEC 6, issue 5), in the order in which a later one that also
// triggers names the stop: steps, time, displacement, load_drop, post_peak_displacement.
// Whether a plate or bar of `sc` moves by a loading program (its end is then a stop rule).
bool has_program(const Scenario& sc);
std::vector<std::unique_ptr<StopRule>> stop_rules(const Scenario& sc, const PeakTracker& peak);

}  // namespace rcdem
