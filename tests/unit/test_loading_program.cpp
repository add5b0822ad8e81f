// Loading programs (solver/loading_program.hpp, issue 41 item 2) driving a linear spring,
// F = K d along the loading direction: the constant program is the cosine ramp it replaced, bit
// for bit; segments end where their goals are met; cycles expand into their moves; the force
// servo reaches its target without overshoot and holds it; a program continued from a copy of its
// state gives the same velocities bit for bit (what a checkpoint restores).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rcdem/core/error.hpp"
#include "rcdem/solver/loading_program.hpp"

using namespace rcdem;

namespace {

// A plate loading a spring of stiffness k downwards (direction -1): load = k * (-d).
struct Spring {
  LoadingProgram program;
  Real k, dt, t = 0.0, d = 0.0;
  Real load() const { return -k * d; }
  Real step() {
    const StepClock clock{t, dt, 1.0};
    const Real v = program.velocity(clock, d, load(), "plates.top");
    d += v * dt;
    t += dt;
    return v;
  }
};

SegmentSettings segment(SegmentKind kind) {
  SegmentSettings s;
  s.kind = kind;
  return s;
}

}  // namespace

TEST(LoadingProgram, ConstantIsTheCosineRampBitwise) {
  LoadingProgram p(-0.1, 4e-3);
  const Real dt = 1.7e-6;
  for (int n = 0; n < 5000; ++n) {
    const Real t = n * dt, mid = t + 0.5 * dt;
    const Real expected = mid >= 4e-3 ? -0.1 : -0.1 * 0.5 * (1.0 - std::cos(kPi * mid / 4e-3));
    ASSERT_EQ(p.velocity({t, dt, 1.0}, 0.0, 0.0, "p"), expected) << n;
  }
  EXPECT_FALSE(p.explicit_program());
}

TEST(LoadingProgram, SegmentsEndWhereTheirGoalsAreMet) {
  SegmentSettings to = segment(SegmentKind::Displacement);
  to.target = -1e-4;
  to.speed = 0.01;
  SegmentSettings hold = segment(SegmentKind::Hold);
  hold.duration = 2e-3;
  SegmentSettings unload = segment(SegmentKind::Load);
  unload.target = 100.0;
  unload.speed = 0.01;
  const std::vector<SegmentSettings> program{to, hold, unload};
  EXPECT_EQ(LoadingProgram::first_direction(program, 1.0), -1.0);
  Spring s{LoadingProgram(program, 2e-4, -1.0), 1e7, 1e-6};
  // Down to the target: the segment ends at the first step past it, by less than a step's move
  // (and that step moves on, its velocity ramping down from the last).
  while (s.program.segment() == 0) s.step();
  EXPECT_LE(s.d, -1e-4);
  EXPECT_GT(s.d, -1e-4 - 2 * 0.0101 * s.dt);
  // The hold: still once the ramp has brought the velocity to 0, for its duration.
  const Real hold_start = s.t - s.dt;
  while (s.program.segment() == 1) s.step();
  EXPECT_NEAR(s.t - s.dt - hold_start, 2e-3, 1.5 * s.dt);
  // Unloading to 100 N: back up until the load is at or below it.
  while (s.program.segment() == 2) {
    s.step();
    ASSERT_LT(s.t, 1.0) << "never unloaded";
  }
  EXPECT_LE(s.load(), 100.0);
  EXPECT_TRUE(s.program.finished());
  // Finished: it comes to rest and stays there.
  for (int n = 0; n < 1000; ++n) s.step();
  EXPECT_EQ(s.step(), 0.0);
}

TEST(LoadingProgram, CyclesReachEachPeakThenUnload) {
  SegmentSettings c = segment(SegmentKind::Cycles);
  c.count = 3;
  c.amplitude = -2e-5;
  c.amplitude_step = -1e-5;
  c.unload_to = 50.0;
  c.speed = 0.01;
  Spring s{LoadingProgram({c}, 1e-4, -1.0), 1e7, 1e-6};
  std::vector<Real> peaks, valleys;
  std::int64_t segment = 0;
  while (!s.program.finished() && s.t < 1.0) {
    s.step();
    if (s.program.segment() != segment) {
      (segment % 2 == 0 ? peaks : valleys).push_back(s.d);
      segment = s.program.segment();
    }
  }
  ASSERT_EQ(peaks.size(), 3U);
  ASSERT_EQ(valleys.size(), 3U);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LE(peaks[k], -2e-5 - 1e-5 * k);
    EXPECT_GT(peaks[k], -2e-5 - 1e-5 * k - 0.011 * s.dt);
    EXPECT_LE(-1e7 * valleys[k], 50.0);
  }
}

// The servo on a spring whose stiffness it measured (the secant at its start): the load reaches
// the target from below, never past it by more than 0.1%, and stays within 1% for the duration.
TEST(LoadingProgram, ForceServoReachesAndHoldsItsTarget) {
  SegmentSettings pre = segment(SegmentKind::Load);
  pre.target = 800.0;
  pre.speed = 0.01;
  SegmentSettings f = segment(SegmentKind::Force);
  f.target = 1000.0;
  f.duration = 3e-3;
  f.response_time = 5e-4;
  f.speed = 0.01;
  Spring s{LoadingProgram({pre, f}, 2e-4, -1.0), 2e7, 1e-6};
  while (s.program.segment() == 0) s.step();
  Real most = 0.0, reached = -1.0, worst = 0.0;
  while (s.program.segment() == 1) {
    s.step();
    most = std::max(most, s.load());
    if (reached < 0.0 && std::abs(s.load() - 1000.0) <= 10.0) reached = s.t;
    if (reached >= 0.0) worst = std::max(worst, std::abs(s.load() - 1000.0) / 1000.0);
  }
  EXPECT_LE(most, 1001.0);
  EXPECT_LE(worst, 0.01);
  EXPECT_NEAR(s.t - reached, 3e-3, 2.5 * s.dt);
  // First order: a quarter of the way there after the blend, the error falls by e per time
  // constant; here simply: within 1% well before 5 time constants from the start.
  EXPECT_GT(reached, 0.0);
}

TEST(LoadingProgram, AForceSegmentWithNoStiffnessToMeasureFails) {
  SegmentSettings f = segment(SegmentKind::Force);
  f.target = 1000.0;
  f.duration = 1e-3;
  f.response_time = 1e-4;
  f.speed = 0.01;
  LoadingProgram p({f}, 0.0, -1.0);
  EXPECT_THROW(p.velocity({0.0, 1e-6, 1.0}, 0.0, 0.0, "plates.top"), Error);
}

// What a checkpoint keeps is all a program needs: a copy continued gives the same bits.
TEST(LoadingProgram, ContinuesBitwiseFromACopyOfItsState) {
  SegmentSettings c = segment(SegmentKind::Cycles);
  c.count = 2;
  c.amplitude = -2e-5;
  c.unload_to = 50.0;
  c.speed = 0.01;
  SegmentSettings f = segment(SegmentKind::Force);
  f.target = 300.0;
  f.duration = 1e-3;
  f.response_time = 2e-4;
  f.speed = 0.01;
  const std::vector<SegmentSettings> program{c, f};
  Spring a{LoadingProgram(program, 1e-4, -1.0), 1e7, 1e-6};
  for (int n = 0; n < 4321; ++n) a.step();
  Spring b{LoadingProgram(program, 1e-4, -1.0), 1e7, 1e-6, a.t, a.d};
  b.program.state() = a.program.state();
  for (int n = 0; n < 20000; ++n) ASSERT_EQ(a.step(), b.step()) << n;
}
