#include "rcdem/core/thread_count_tuner.hpp"

#include <algorithm>
#include <chrono>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace rcdem {

ThreadCountTuner::ThreadCountTuner(const ThreadTuning& tuning)
    : t_(tuning),
      chosen_(std::max(1, tuning.max_threads)),
      running_(chosen_),
      next_check_(0.0),  // a run that starts on a loaded machine checks after its first window
      check_interval_(tuning.first_check_seconds) {}

void ThreadCountTuner::after_step(double seconds) {
  if (t_.max_threads <= 1) return;
  clock_ += seconds;
  window_seconds_ += seconds;
  if (++window_steps_ < t_.window_steps || window_seconds_ < t_.window_seconds) return;
  // A window of zero time (a clock too coarse for it) counts as no change.
  const double rate =
      window_seconds_ > 0.0 ? static_cast<double>(window_steps_) / window_seconds_ : reference_;
  window_steps_ = 0;
  window_seconds_ = 0.0;
  window_done(rate);
}

void ThreadCountTuner::window_done(double rate) {
  switch (phase_) {
    case Phase::Measure: {
      const bool jumped =
          reference_ > 0.0 && (rate * t_.jump < reference_ || rate > t_.jump * reference_);
      reference_ = rate;
      if (jumped) check_interval_ = t_.first_check_seconds;
      if (jumped || clock_ >= next_check_) start_check();
      return;
    }
    case Phase::Below:
      below_ = rate;
      below_count_ = running_;
      // Neither faster nor slower: every count above the free cores is equally slow, so the
      // check goes on down, twice as far each time, while it finds the same rate.
      if (rate <= t_.gain * reference_ && rate * t_.gain >= reference_ && running_ > 1) {
        running_ = std::max(1, chosen_ - 2 * (chosen_ - below_count_));
        return;
      }
      if (chosen_ < t_.max_threads) {
        phase_ = Phase::Above;
        running_ = chosen_ + 1;
        return;
      }
      measure_again();
      return;
    case Phase::Above:
      above_ = rate;
      measure_again();
      return;
    case Phase::Again: {
      // The present count's rate before and after the checks, so that a neighbour's load that
      // came or went during them does not pass for a better count.
      const double before = reference_;
      reference_ = rate;
      decide(std::max(before, rate));
      return;
    }
  }
}

// A check whose best count is more than `jump` times faster is decided at once: a count above
// the free cores need not be timed again.
void ThreadCountTuner::measure_again() {
  if (std::max(below_, above_) > t_.jump * reference_) {
    decide(reference_);
    return;
  }
  phase_ = Phase::Again;
  running_ = chosen_;
}

void ThreadCountTuner::start_check() {
  below_ = above_ = 0.0;
  phase_ = chosen_ > 1 ? Phase::Below : Phase::Above;
  running_ = chosen_ > 1 ? chosen_ - 1 : chosen_ + 1;
}

// The fastest of the counts checked, where it beats the present one (steps/s `present`) by the
// gain. After a change the new count's neighbours are checked at once (a collapse may need
// several steps down).
void ThreadCountTuner::decide(double present) {
  const bool below_best = below_ >= above_;
  const double best = below_best ? below_ : above_;
  if (best > t_.gain * present) {
    chosen_ = below_best ? below_count_ : chosen_ + 1;
    reference_ = best;
    ++changes_;
    check_interval_ = t_.first_check_seconds;
    next_check_ = clock_;
  } else {
    check_interval_ = std::min(2.0 * check_interval_, t_.last_check_seconds);
    next_check_ = clock_ + check_interval_;
  }
  phase_ = Phase::Measure;
  running_ = chosen_;
}

int runtime_thread_count() {
#if defined(_OPENMP)
  return omp_get_max_threads();
#else
  return 1;
#endif
}

void set_runtime_thread_count(int threads) {
#if defined(_OPENMP)
  omp_set_num_threads(std::max(1, threads));
#else
  (void)threads;
#endif
}

namespace {

ThreadTuning tuning_up_to(int threads) {
  ThreadTuning t;
  t.max_threads = threads;
  return t;
}

}  // namespace

StepThreads::StepThreads(int fixed) : StepThreads(fixed, tuning_up_to(runtime_thread_count())) {}

StepThreads::StepThreads(int fixed, const ThreadTuning& tuning)
    : runtime_count_(runtime_thread_count()),
      tuned_(fixed <= 0 && tuning.max_threads > 1),
      tuner_([&] {
        ThreadTuning t = tuning;
        if (fixed > 0) t.max_threads = fixed;
        return t;
      }()) {
  set_runtime_thread_count(tuner_.threads());
}

StepThreads::~StepThreads() { set_runtime_thread_count(runtime_count_); }

double StepThreads::now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void StepThreads::after_step(double seconds) {
  ++steps_;
  thread_steps_ += tuner_.threads();
  step_seconds_ += seconds;
  if (!tuned_) return;
  const int before = tuner_.threads();
  tuner_.after_step(seconds);
  if (tuner_.threads() != before) set_runtime_thread_count(tuner_.threads());
}

ThreadRecord StepThreads::record() const {
  ThreadRecord r;
  r.tuned = tuned_;
  r.max = tuned_ ? runtime_count_ : tuner_.threads();
  r.last = tuner_.chosen();
  r.mean = steps_ > 0 ? thread_steps_ / static_cast<double>(steps_) : tuner_.threads();
  r.changes = tuner_.changes();
  r.step_seconds = step_seconds_;
  return r;
}

}  // namespace rcdem
