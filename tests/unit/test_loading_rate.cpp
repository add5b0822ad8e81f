// loading.adaptive_rate's controller (solver/loading_rate.hpp) on ledgers made by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "rcdem/solver/loading_rate.hpp"

using namespace rcdem;

namespace {

// A ledger with work W, kinetic energy K, damage dissipation D and strain energy W - K - D.
Energy ledger(Real work, Real kinetic, Real damage) {
  Energy e;
  e.external_work = work;
  e.kinetic = kinetic;
  e.damage = damage;
  return e;
}

LoadingRateSettings on() {
  LoadingRateSettings s;
  s.adaptive = true;
  s.max_factor = 4.0;
  s.kinetic_ratio = 0.01;
  s.damage_work_ratio = 0.5;
  s.doubling_time = 1e-3;
  return s;
}

// Runs `checks` checks of a controller with a ledger that gains `dw` work, `dd` damage per
// check and holds kinetic/strain = ratio; returns the factor.
Real drive(LoadingRate& r, int checks, Real ratio, Real dw, Real dd, Real dt, Real& work,
           Real& damage, std::int64_t& step) {
  for (int k = 0; k < checks; ++k) {
    work += dw;
    damage += dd;
    const Real strain_and_kinetic = work - damage;
    const Real kinetic = strain_and_kinetic * ratio / (1 + ratio);
    step += LoadingRate::kCheckSteps;
    r.update(step, dt, ledger(work, kinetic, damage));
  }
  return r.factor();
}

}  // namespace

// Off: the factor is 1 whatever the ledger says.
TEST(LoadingRate, OffKeepsTheSetSpeed) {
  LoadingRate r;
  Real w = 0, d = 0;
  std::int64_t n = 0;
  EXPECT_EQ(drive(r, 1000, 0.0, 1.0, 0.0, 1e-6, w, d, n), 1.0);
}

// Quasi-static and intact: the factor about doubles per doubling time (1 + ln 2 x per check, so
// 2 within 1%), and stops at max_factor; checks fall every 20 steps only.
TEST(LoadingRate, RisesAboutTwofoldPerDoublingTimeUpToTheMaximum) {
  LoadingRate r(on());
  const Real dt = 1e-6;  // a check every 20 us: 50 checks per doubling time
  Real w = 0, d = 0;
  std::int64_t n = 0;
  r.update(7, dt, ledger(1.0, 0.0, 0.0));  // not a check step: nothing happens
  EXPECT_EQ(r.factor(), 1.0);
  const Real f = drive(r, 50, 0.001, 1.0, 0.0, dt, w, d, n);
  EXPECT_NEAR(f, 2.0, 0.02);
  EXPECT_EQ(drive(r, 500, 0.001, 1.0, 0.0, dt, w, d, n), 4.0);
}

// Too much kinetic energy, or a crack burst (damage above half the work of the interval): the
// factor falls four times as fast as it rose, to 1 and no lower; in between it holds.
TEST(LoadingRate, FallsOnKineticEnergyOrACrackBurstAndHoldsInBetween) {
  const Real dt = 1e-6;
  for (const bool burst : {false, true}) {
    LoadingRate r(on());
    Real w = 0, d = 0;
    std::int64_t n = 0;
    ASSERT_EQ(drive(r, 500, 0.001, 1.0, 0.0, dt, w, d, n), 4.0);
    const Real ratio = burst ? 0.001 : 0.02;
    const Real dd = burst ? 0.6 : 0.0;
    const Real f = drive(r, 13, ratio, 1.0, dd, dt, w, d, n);  // a quarter doubling time
    EXPECT_NEAR(f, 2.0, 0.1) << burst;
    EXPECT_EQ(drive(r, 200, ratio, 1.0, dd, dt, w, d, n), 1.0);
  }
  LoadingRate hold(on());
  Real w = 0, d = 0;
  std::int64_t n = 0;
  const Real f = drive(hold, 50, 0.001, 1.0, 0.0, dt, w, d, n);
  EXPECT_EQ(drive(hold, 100, 0.007, 1.0, 0.4, dt, w, d, n), f);  // 0.005 < K/S < 0.01, D < W/2
}
