// The thread count that follows the free cores (core/thread_count_tuner.hpp). The tuner is fed
// step times from a model of a shared machine: a count up to the free cores steps at
// rate(1) T^0.85; one more thread than the free cores makes every parallel loop wait for the
// descheduled thread, and the step falls to 0.19 of 1 thread's rate (measured on 16 cores,
// bench/RESULTS.md "Many cores"). And a run whose count changes between steps, as the tuner
// makes it, gives the same bits as one thread.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>

#include "rcdem/core/thread_count_tuner.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "small_scenarios.hpp"

using namespace rcdem;

namespace {

constexpr double kOneThreadRate = 400.0;  // steps/s

// A shared machine: `free` cores left by other work; step times with a +-`noise` jitter, and
// bursts of other tenants' load: every `burst_period` seconds the whole machine's speed is drawn
// anew between 1 - `burst` and 1.
struct SharedMachine {
  int free = 16;
  double noise = 0.03;
  double burst = 0.0, burst_period = 0.3;
  double memory_bound = 1e30;  // the most steps/s the memory gives, at any count
  std::mt19937_64 rng{7};
  double clock = 0.0, next_burst = 0.0, speed = 1.0;
  double rate(int threads) const {
    if (threads > free) return 0.19 * kOneThreadRate;
    return std::min(kOneThreadRate * std::pow(threads, 0.85), memory_bound);
  }
  double step_seconds(int threads) {
    if (clock >= next_burst) {
      speed = std::uniform_real_distribution<double>(1.0 - burst, 1.0)(rng);
      next_burst = clock + burst_period;
    }
    std::uniform_real_distribution<double> jitter(1.0 - noise, 1.0 + noise);
    const double dt = jitter(rng) / (speed * rate(threads));
    clock += dt;
    return dt;
  }
};

// Feeds the tuner steps for `seconds` of the machine's time; returns the steps taken.
double run_for(ThreadCountTuner& tuner, SharedMachine& machine, double seconds) {
  double steps = 0.0;
  for (double t = 0.0; t < seconds;) {
    const double dt = machine.step_seconds(tuner.threads());
    tuner.after_step(dt);
    t += dt;
    steps += 1.0;
  }
  return steps;
}

ThreadTuning up_to(int threads) {
  ThreadTuning t;
  t.max_threads = threads;
  return t;
}

}  // namespace

// A quiet machine keeps every core: the checks at one thread fewer cost under 1% of the steps.
TEST(ThreadCountTuner, AQuietMachineKeepsEveryCore) {
  SharedMachine machine;
  ThreadCountTuner tuner(up_to(16));
  const double steps = run_for(tuner, machine, 300.0);
  EXPECT_EQ(tuner.chosen(), 16);
  EXPECT_EQ(tuner.changes(), 0);
  EXPECT_GT(steps, 0.99 * 300.0 * machine.rate(16));
}

// Two cores taken: the count steps down to the 14 free ones within seconds, the run keeps 0.95 of
// what 14 threads give, and it climbs back to 16 once the cores are free again.
TEST(ThreadCountTuner, FollowsCoresTakenAndGivenBack) {
  SharedMachine machine;
  ThreadCountTuner tuner(up_to(16));
  run_for(tuner, machine, 20.0);
  ASSERT_EQ(tuner.chosen(), 16);
  machine.free = 14;
  run_for(tuner, machine, 5.0);
  EXPECT_EQ(tuner.chosen(), 14);
  const double busy = run_for(tuner, machine, 120.0);
  EXPECT_EQ(tuner.chosen(), 14);
  EXPECT_GT(busy, 0.95 * 120.0 * machine.rate(14));
  machine.free = 16;
  run_for(tuner, machine, 2.0 * up_to(16).last_check_seconds + 2.0);
  EXPECT_EQ(tuner.chosen(), 16);
}

// A run that starts with a core taken finds the free ones within its first second.
TEST(ThreadCountTuner, ARunStartingOnALoadedMachineFindsTheFreeCoresAtOnce) {
  SharedMachine machine;
  machine.free = 15;
  ThreadCountTuner tuner(up_to(16));
  run_for(tuner, machine, 1.0);
  EXPECT_EQ(tuner.chosen(), 15);
}

// Half the cores taken: every count from 9 to 16 is as slow as the next, so the check goes down
// past them (15, 14, 12, 8) and takes 8 within seconds.
TEST(ThreadCountTuner, HalfTheCoresTakenIsFoundPastTheEquallySlowCounts) {
  SharedMachine machine;
  ThreadCountTuner tuner(up_to(16));
  run_for(tuner, machine, 10.0);
  machine.free = 8;
  run_for(tuner, machine, 5.0);
  EXPECT_EQ(tuner.chosen(), 8);
  const double busy = run_for(tuner, machine, 120.0);
  EXPECT_GT(busy, 0.95 * 120.0 * machine.rate(8));
}

// A memory-bound step (12 to 16 threads equally fast) on a quiet machine keeps every core: the
// check goes down the equal counts and stops at the first slower one.
TEST(ThreadCountTuner, AMemoryBoundStepKeepsEveryCore) {
  SharedMachine machine;
  machine.memory_bound = 3000.0;
  ThreadCountTuner tuner(up_to(16));
  const double steps = run_for(tuner, machine, 300.0);
  EXPECT_EQ(tuner.chosen(), 16);
  EXPECT_GT(steps, 0.99 * 300.0 * machine.rate(16));
}

// Issue 43's measure on two cores with one taken: never below 0.9 of 1 thread's rate.
TEST(ThreadCountTuner, TwoCoresOneTakenKeepsOneThreadsRate) {
  SharedMachine machine;
  machine.free = 1;
  ThreadCountTuner tuner(up_to(2));
  const double steps = run_for(tuner, machine, 60.0);
  EXPECT_EQ(tuner.chosen(), 1);
  EXPECT_GT(steps, 0.9 * 60.0 * machine.rate(1));
}

// Noise of +-10% between steps does not make a quiet machine's count wander.
TEST(ThreadCountTuner, NoiseDoesNotMoveTheCount) {
  SharedMachine machine;
  machine.free = 2;
  machine.noise = 0.10;
  ThreadCountTuner tuner(up_to(2));
  run_for(tuner, machine, 300.0);
  EXPECT_EQ(tuner.chosen(), 2);
  EXPECT_LE(tuner.changes(), 2);
}

// Other tenants' bursts (the machine's speed changing by up to 15% every 0.3 s) on a quiet,
// memory-bound 16 cores: the count stays put and the run keeps 0.97 of every core's rate.
TEST(ThreadCountTuner, BurstsOfOtherLoadDoNotMoveTheCount) {
  SharedMachine machine;
  machine.burst = 0.15;
  machine.memory_bound = 3000.0;
  ThreadCountTuner tuner(up_to(16));
  const double steps = run_for(tuner, machine, 300.0);
  EXPECT_EQ(tuner.chosen(), 16);
  EXPECT_LE(tuner.changes(), 2);
  EXPECT_GT(steps, 0.97 * 300.0 * 0.925 * machine.rate(16));
}

TEST(ThreadCountTuner, OneThreadIsNeverTuned) {
  SharedMachine machine;
  ThreadCountTuner tuner(up_to(1));
  run_for(tuner, machine, 30.0);
  EXPECT_EQ(tuner.threads(), 1);
  EXPECT_EQ(tuner.changes(), 0);
}

// The count changed between steps (a check after every step, so the run moves between 1, 2 and 3
// threads) gives the same bits as one thread throughout: nothing of a step depends on the count.
TEST(ThreadCountTuner, ACountThatChangesBetweenStepsGivesTheSameBits) {
#if !defined(_OPENMP)
  GTEST_SKIP() << "built without OpenMP: one thread only";
#endif
  const Scenario sc = test::pulled_box();
  constexpr int kSteps = 2500;  // through the peak (about step 1,500)
  Simulation fixed(sc, build_specimen(sc)), tuned(sc, build_specimen(sc));
  std::set<int> counts;
  {
    StepThreads one(1);
    for (int k = 0; k < kSteps; ++k) one.step([&] { fixed.step(); });
  }
  {
    ThreadTuning every_step = up_to(3);
    every_step.window_seconds = 0.0;
    every_step.window_steps = 1;
    every_step.first_check_seconds = every_step.last_check_seconds = 0.0;
    StepThreads moving(0, every_step);
    for (int k = 0; k < kSteps; ++k)
      moving.step([&] {
        counts.insert(runtime_thread_count());
        tuned.step();
      });
  }
  EXPECT_GE(counts.size(), 2u);
  EXPECT_GT(fixed.damaged_points(), 0);
  EXPECT_EQ(fixed.find_plate("top")->force.z(), tuned.find_plate("top")->force.z());
  EXPECT_EQ(fixed.strain_energy(), tuned.strain_energy());
  EXPECT_EQ(fixed.damaged_points(), tuned.damaged_points());
  EXPECT_EQ(fixed.broken_points(), tuned.broken_points());
}
