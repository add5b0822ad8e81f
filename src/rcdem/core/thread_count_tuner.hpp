#pragma once
// How many threads the step uses, chosen from the step's own measured rate (issue 43, item 3).
// On a machine shared with other work, one thread more than the cores left free makes every
// parallel loop of the step wait a time slice for the thread that shares a core: 16 threads with
// one of 16 cores taken stepped at 0.19 of 1 thread's rate, 15 threads at 7.1 times it
// (bench/RESULTS.md, "Many cores"). The results are the same bits at any thread count, so the
// count may follow the free cores during a run: every so often the step is timed one window at
// one thread fewer and one more than the present count, then at the present count again, and the
// fastest is kept where it beats the present count before and after the checks; where the count
// below is no faster and no slower (every count above the free cores is as slow as the next), the
// check goes on down, 2, 4, 8 ... threads below the present count. A rate that
// jumps (a neighbour starts or stops) checks at once; a check that changes nothing waits twice as
// long before the next (in the manner of GROMACS's run-time tuning, which times its alternatives
// during the run rather than guessing from the machine's load).
#include <cstdint>

namespace rcdem {

struct ThreadTuning {
  int max_threads = 1;            // the most the step may use (OMP_NUM_THREADS or the cores)
  double window_seconds = 0.2;    // a rate is measured over at least this long ...
  std::int64_t window_steps = 3;  // ... and this many steps
  // The neighbouring counts are timed after the first window, at once after a change, and then
  // after 2x first_check_seconds, doubling after each check that changes nothing, up to
  // last_check_seconds.
  double first_check_seconds = 5;
  double last_check_seconds = 40;
  double gain = 1.05;  // another count is taken only when this much faster
  double jump = 1.5;   // a window this much slower or faster checks at once
};

// The decision alone, fed the wall time of each step (testable with made-up times).
class ThreadCountTuner {
 public:
  explicit ThreadCountTuner(const ThreadTuning& tuning);
  int threads() const { return running_; }  // the count the next step runs at
  int chosen() const { return chosen_; }    // the count kept between checks
  std::int64_t changes() const { return changes_; }
  // The wall time of the step just taken at threads().
  void after_step(double seconds);

 private:
  enum class Phase { Measure, Below, Above, Again };
  void window_done(double rate);
  void start_check();
  void measure_again();
  void decide(double present);

  ThreadTuning t_;
  int chosen_, running_;
  Phase phase_ = Phase::Measure;
  std::int64_t window_steps_ = 0;
  double window_seconds_ = 0.0;
  double clock_ = 0.0, next_check_, check_interval_;
  // Steps/s at the chosen count, at the last count checked below it, and at one above it.
  double reference_ = 0.0, below_ = 0.0, above_ = 0.0;
  int below_count_ = 1;
  std::int64_t changes_ = 0;
};

// What a run reports of its thread counts (summary.json's "threads") and of the time its steps
// took (its "step_seconds", which the timing for the tuner gives for nothing).
struct ThreadRecord {
  bool tuned = false;
  int max = 1, last = 1;
  double mean = 1.0;  // over the steps
  std::int64_t changes = 0;
  double step_seconds = 0.0;  // wall time inside the steps
};

// The tuner applied to the OpenMP runtime around each step. `fixed` > 0 runs exactly that many
// threads; 0 follows the free cores up to the runtime's count (OMP_NUM_THREADS, or the cores).
// The runtime's count is put back when it ends, so that a later run in the same process (Python)
// starts from it.
class StepThreads {
 public:
  explicit StepThreads(int fixed = 0);
  ~StepThreads();
  StepThreads(const StepThreads&) = delete;
  StepThreads& operator=(const StepThreads&) = delete;
  // A tuner with other windows (tests).
  StepThreads(int fixed, const ThreadTuning& tuning);
  // Runs one step at the present count and times it for the tuner.
  template <typename Step>
  void step(Step&& one_step) {
    const double t0 = now();
    one_step();
    after_step(now() - t0);
  }
  ThreadRecord record() const;

 private:
  static double now();
  void after_step(double seconds);

  int runtime_count_;
  bool tuned_;
  ThreadCountTuner tuner_;
  std::int64_t steps_ = 0;
  double thread_steps_ = 0.0, step_seconds_ = 0.0;
};

// The runtime's thread count (1 without OpenMP), and setting it for the next parallel loops.
int runtime_thread_count();
void set_runtime_thread_count(int threads);

}  // namespace rcdem
