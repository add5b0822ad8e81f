#include "rcdem/run/observers.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rcdem/core/progress.hpp"

namespace rcdem {

void PeakTracker::act(const StepView& step) {
  if (!(step.load > s_.peak)) return;
  s_.peak = step.load;
  s_.displacement_at_peak = step.displacement;
  // The strain energy from the balance of SPEC 11 (W = E_s + E_k + D, kept within 1e-4): summing
  // it over a million local points at every new peak would cost a step's time.
  const Energy& e = step.sim.ledger();
  const Real strain = e.external_work - e.kinetic - e.dissipated();
  s_.kinetic_over_strain_at_peak = strain > 0.0 ? e.kinetic / strain : 0.0;
}

void HistoryRecorder::act(const StepView& step) {
  history_.record(step.sim);
  cracks_.update(step.sim, step.displacement, step.load);
}

void SnapshotRecorder::act(const StepView& step) {
  snapshots_.write(step.sim);
  history_.write(out_ / "history.csv");
}

ProgressLine::ProgressLine(Real expected_steps, const PeakTracker& peak)
    : RunObserver(Trigger::every(Progress::quiet_default() ? 0 : 1)),
      expected_(expected_steps),
      peak_(peak),
      tty_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void ProgressLine::act(const StepView& step) {
  if (first_step_ < 0) first_step_ = step.step - 1;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() <= (tty_ ? 0.5 : 10.0)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = static_cast<double>(step.step - first_step_) / elapsed;
  const double frac = std::min(1.0, static_cast<double>(step.step) / expected_);
  fmt::print(stderr,
             "{}step {} ({:.1f}%)  {:.0f} steps/s  ETA {:.0f} s  load {:.4g} N  peak {:.4g} N{}",
             tty_ ? "\r" : "", step.step, 100.0 * frac, rate,
             rate > 0 ? std::max(0.0, expected_ - static_cast<double>(step.step)) / rate : 0.0,
             step.load, peak_.peak(), tty_ ? "   " : "\n");
  std::fflush(stderr);
}

void ProgressLine::close() const {
  if (trigger().period() > 0 && tty_) fmt::print(stderr, "\n");
}

namespace {

class StepsRule final : public StopRule {
 public:
  explicit StepsRule(std::int64_t steps) : steps_(steps) {}
  const char* reason() const override { return "steps"; }
  bool triggered(const StepView& v) const override { return v.step >= steps_; }

 private:
  std::int64_t steps_;
};

class TimeRule final : public StopRule {
 public:
  explicit TimeRule(Real time) : time_(time) {}
  const char* reason() const override { return "time"; }
  bool triggered(const StepView& v) const override { return v.sim.time() >= time_; }

 private:
  Real time_;
};

class DisplacementRule final : public StopRule {
 public:
  explicit DisplacementRule(Real d) : d_(d) {}
  const char* reason() const override { return "displacement"; }
  bool triggered(const StepView& v) const override { return std::abs(v.displacement) >= d_; }

 private:
  Real d_;
};

// After the peak: the load has fallen below the fraction, and the peak is a real one (the
// specimen has cracked: some local point is fully broken).
class LoadDropRule final : public StopRule {
 public:
  LoadDropRule(Real fraction, const PeakTracker& peak) : fraction_(fraction), peak_(peak) {}
  const char* reason() const override { return "load_drop"; }
  bool triggered(const StepView& v) const override {
    return peak_.peak() > 0.0 && v.load < fraction_ * peak_.peak() && v.sim.ledger().damage > 0.0;
  }

 private:
  Real fraction_;
  const PeakTracker& peak_;
};

// Peak plus a defined post-peak (issue 5): the control has gone this far past the peak's
// position, again only once the specimen has cracked.
class PostPeakRule final : public StopRule {
 public:
  PostPeakRule(Real travel, const PeakTracker& peak) : travel_(travel), peak_(peak) {}
  const char* reason() const override { return "post_peak_displacement"; }
  bool triggered(const StepView& v) const override {
    return peak_.peak() > 0.0 &&
           std::abs(v.displacement) - std::abs(peak_.displacement_at_peak()) >= travel_ &&
           v.sim.ledger().damage > 0.0;
  }

 private:
  Real travel_;
  const PeakTracker& peak_;
};

// Every loading program has run its last segment (a rule wherever the scenario has a program).
class ProgramEndRule final : public StopRule {
 public:
  const char* reason() const override { return "program_end"; }
  bool triggered(const StepView& v) const override {
    for (const Plate& p : v.sim.plates())
      if (p.motion.explicit_program() && !p.motion.finished()) return false;
    for (const PulledBar& b : v.sim.pulled_bars())
      if (b.motion.explicit_program() && !b.motion.finished()) return false;
    return true;
  }
};

}  // namespace

bool has_program(const Scenario& sc) {
  for (const auto& p : sc.plates)
    if (!p.program.empty()) return true;
  for (const auto& b : sc.bars)
    if (!b.program.empty()) return true;
  return false;
}

std::vector<std::unique_ptr<StopRule>> stop_rules(const Scenario& sc, const PeakTracker& peak) {
  std::vector<std::unique_ptr<StopRule>> rules;
  const StopSettings& s = sc.stop;
  if (s.steps > 0) rules.push_back(std::make_unique<StepsRule>(s.steps));
  if (s.time > 0.0) rules.push_back(std::make_unique<TimeRule>(s.time));
  if (s.displacement > 0.0) rules.push_back(std::make_unique<DisplacementRule>(s.displacement));
  if (s.load_drop > 0.0) rules.push_back(std::make_unique<LoadDropRule>(s.load_drop, peak));
  if (s.post_peak_displacement > 0.0)
    rules.push_back(std::make_unique<PostPeakRule>(s.post_peak_displacement, peak));
  if (has_program(sc)) rules.push_back(std::make_unique<ProgramEndRule>());
  return rules;
}

}  // namespace rcdem
