// SPEC 6's time step sqrt(m / sum k) from each body's own 6x6 stiffness block
// (solver/body_stiffness.hpp), against analytic values and against the eigenvalues of a whole
// specimen's assembled stiffness.
//
// The bracket tested in 3: for a unit generalised displacement on one body alone the Rayleigh
// quotient of the assembly is that body's block, so lambda_max(assembly) >= max block lambda; and
// a spring between bodies i, j adds B^T S B with B = [B_i, -B_j] <= 2 (B_i^T S B_i + B_j^T S B_j),
// so lambda_max(assembly) <= 2 max block lambda. With the central-difference limit
// dt_crit = 2 / omega_max, the estimate dt_est = 1 / sqrt(max block lambda) satisfies
// dt_crit / 2 <= dt_est <= dt_crit / sqrt(2): SPEC 6's safety 0.5 runs at most 0.354 dt_crit.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "dynamics_checks.hpp"
#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/rng.hpp"
#include "rcdem/solver/body_stiffness.hpp"
#include "rcdem/solver/selective_mass_scaling.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "static_model.hpp"

using namespace rcdem;

// 1. One spring k_n along x (k_s = 0) at arm (0, rho, 0): u_x = dx - rho dtheta_z, so the block
// is k_n [[1, -rho], [-rho, rho^2]] in (x, theta_z) and lambda_max = k_n (1/m + rho^2 / I).
TEST(BodyStiffness, SpringAtLeverArmCouplesTranslationAndRotation) {
  const Real kn = 3e7, m = 2e-3, I = 5e-9, rho = 4e-3;
  BodyStiffness k(1);
  k.add_spring(0, Vec3::UnitX(), kn, 0.0, Vec3(0, rho, 0));
  const BodyStiffness::Limit l = k.limit(0, m, Vec3(I, I, I), Mat3::Identity());
  EXPECT_NEAR(l.time_step, 1.0 / std::sqrt(kn * (1 / m + rho * rho / I)), 1e-12 * l.time_step);
  EXPECT_TRUE(l.rotation);  // rho^2 / I = 3200 > 1 / m = 500
  EXPECT_EQ(l.body_axis, 2);
  // Only translation if the spring acts through the centre.
  BodyStiffness c(1);
  c.add_spring(0, Vec3::UnitX(), kn, 0.0, Vec3(rho, 0, 0));
  const BodyStiffness::Limit lc = c.limit(0, m, Vec3(I, I, I), Mat3::Identity());
  EXPECT_NEAR(lc.time_step, std::sqrt(m / kn), 1e-12 * lc.time_step);
  EXPECT_FALSE(lc.rotation);
}

// 2. Three springs k_n along x, y, z and k_s across, through the centre: the translational block
// is (k_n + 2 k_s) I, whichever is the stiffer; a rotation of a cylinder about its own axis is
// read in the body's principal frame (inertia (I_t, I_t, I_a), axis z turned to world x).
TEST(BodyStiffness, IsotropicSpringsAndPrincipalFrame) {
  const Real kn = 2e7, ks = 0.3 * kn, m = 1e-3;
  BodyStiffness k(1);
  for (int a = 0; a < 3; ++a) k.add_spring(0, Vec3::Unit(a), kn, ks, Vec3::Zero());
  EXPECT_NEAR(k.limit(0, m, Vec3(1, 1, 1), Mat3::Identity()).time_step,
              std::sqrt(m / (kn + 2 * ks)), 1e-12);
  // A torsion spring about world x on a cylinder whose body z is world x.
  Mat3 axes;
  axes << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // columns: body x, y, z in the world
  const Real kt = 5.0, It = 1e-6, Ia = 1e-8;
  BodyStiffness t(1);
  t.add_rotational(0, kt * Vec3::UnitX() * Vec3::UnitX().transpose());
  const BodyStiffness::Limit l = t.limit(0, m, Vec3(It, It, Ia), axes);
  EXPECT_NEAR(l.time_step, std::sqrt(Ia / kt), 1e-12 * l.time_step);
  EXPECT_TRUE(l.rotation);
  EXPECT_EQ(l.body_axis, 2);
}

namespace {

Scenario glued_box(Real size, Real alpha, Real inertia_scaling, Real added_mass_limit = 0.0) {
  return test::elastic_box(size,
                           fmt::format("dt_safety = 0.5\nparticle_rotational_inertia_scaling = "
                                       "{}\nadded_mass_limit = {}\n",
                                       inertia_scaling, added_mass_limit) +
                               test::glued_platens(),
                           0.0, alpha);
}

// The estimate lies in [dt_crit / 2, dt_crit / sqrt 2] of the assembly's own omega_max (with its
// masses as built), and fresh simulations of `sc` run stably just below dt_crit and blow up just
// above it. Returns dt_crit.
Real expect_estimate_brackets_critical_step(const Scenario& sc, const Specimen& sp,
                                            const Simulation& sim) {
  const Real dt_crit = 2.0 / test::highest_frequency(sim);
  const Real est = sim.stable_time_step();
  EXPECT_GE(est, 0.5 * dt_crit * (1 - 1e-6));
  EXPECT_LE(est, dt_crit / std::sqrt(2.0) * (1 + 1e-6));
  Simulation below(sc, sp), above(sc, sp);
  EXPECT_TRUE(test::runs_stably(below, 0.97 * dt_crit, 3000));
  EXPECT_FALSE(test::runs_stably(above, 1.05 * dt_crit, 3000));
  return dt_crit;
}

}  // namespace

// 3. On glued-plate boxes (alpha 0.3 and 3, particle inertia as SPEC 6 and x2.5) the estimate
// lies in [dt_crit / 2, dt_crit / sqrt 2] of the assembly's own omega_max, and the solver is
// stable just below dt_crit and unstable just above: the estimate is about the dynamics that run.
TEST(TimeStep, EstimateBracketsTheAssemblysCriticalStep) {
  struct Case {
    Real alpha, inertia_scaling;
  };
  for (const Case c : {Case{0.3, 1.0}, Case{3.0, 1.0}, Case{0.3, 2.5}}) {
    const Scenario sc = glued_box(0.025, c.alpha, c.inertia_scaling);
    const Specimen sp = build_specimen(sc);
    Simulation sim(sc, sp);
    ASSERT_GT(sim.bodies().size(), 30);
    const Real dt_crit = expect_estimate_brackets_critical_step(sc, sp, sim);
    const Real est = sim.stable_time_step();
    EXPECT_LE(sim.time_step(), 0.36 * dt_crit);
    std::printf(
        "[time step, alpha %.1f, inertia x%.1f] %lld bodies: estimate %.4g s = %.3f dt_crit "
        "(dt_crit = 2 / omega_max = %.4g s); set by %s\n",
        c.alpha, c.inertia_scaling, (long long)sim.bodies().size(), est, est / dt_crit, dt_crit,
        sim.stable_time_step_limit().c_str());
  }
}

// 4. Selective mass scaling (solver/selective_mass_scaling.hpp). The plan, by hand: steps
// {4, 1, 2, inf, 3} s with masses {1, 2, 1, 5, 1} kg (total 10). Raising the k shortest to T adds
// T^2 sum(m / dt^2) - sum(m): with 1 kg allowed, body 1 alone, 2 (T^2 - 1) = 1, T = sqrt(1.5);
// with 10 kg, body 1 would pass body 2's 2 s, so both: 2.25 T^2 - 3 = 10, T = sqrt(13 / 2.25).
TEST(SelectiveMassScaling, PlanRaisesTheShortestStepsWithinTheAddedMass) {
  const Real inf = std::numeric_limits<Real>::infinity();
  const std::vector<Real> step{4, 1, 2, inf, 3}, mass{1, 2, 1, 5, 1};
  struct Case {
    Real limit, target;
    Index scaled;
  };
  for (const Case c : {Case{0.1, std::sqrt(1.5), 1}, Case{0.5, std::sqrt(3.5), 1},
                       Case{1.0, std::sqrt(13 / 2.25), 2}}) {
    const MassScalingPlan p = plan_selective_mass_scaling(step, mass, c.limit);
    EXPECT_NEAR(p.time_step, c.target, 1e-14 * c.target) << c.limit;
    EXPECT_EQ(p.unscaled_step, 1.0);
    EXPECT_EQ(p.total_mass, 10.0);
    EXPECT_EQ(p.bodies_scaled, c.scaled);
    EXPECT_NEAR(p.added_mass, c.limit * p.total_mass, 1e-13);
    Real added = 0;
    for (std::size_t i = 0; i < step.size(); ++i) {
      // Each raised body's estimate, sqrt(f) dt, is the target; the others are untouched.
      if (step[i] < c.target) {
        EXPECT_NEAR(std::sqrt(p.factor[i]) * step[i], c.target, 1e-14 * c.target);
      } else {
        EXPECT_EQ(p.factor[i], 1.0);
      }
      added += mass[i] * (p.factor[i] - 1);
    }
    EXPECT_NEAR(added, p.added_mass, 1e-13);
    EXPECT_NEAR(p.largest_factor, c.target * c.target, 1e-13);
  }
  // Off: the identity, exactly.
  const MassScalingPlan off = plan_selective_mass_scaling(step, mass, 0.0);
  EXPECT_EQ(off.time_step, 1.0);
  EXPECT_EQ(off.bodies_scaled, 0);
  EXPECT_EQ(off.added_mass, 0.0);
  for (const Real f : off.factor) EXPECT_EQ(f, 1.0);
  // A budget beyond every finite step raises them all: 1.25 T^2 - 2 = 20.
  const MassScalingPlan all = plan_selective_mass_scaling({1, 2}, {1, 1}, 10.0);
  EXPECT_NEAR(all.time_step, std::sqrt(22 / 1.25), 1e-14);
  EXPECT_EQ(all.bodies_scaled, 2);
}

// 5. On a glued box, the scaled specimen's estimate is the plan's target, longer than without
// scaling, the specimen is heavier by exactly the fraction allowed, and the estimate still
// brackets the critical step of the assembly with its new masses (stable at 0.97 dt_crit,
// unstable at 1.05): each raised body's own estimate is lifted to the target, and no further.
TEST(SelectiveMassScaling, ScaledSpecimenKeepsTheCriticalStepBracket) {
  const Real limit = 0.03;
  const Scenario plain = glued_box(0.025, 0.3, 2.5);
  const Scenario scaled = glued_box(0.025, 0.3, 2.5, limit);
  const Specimen sp = build_specimen(plain);
  const Simulation before(plain, sp);
  Simulation sim(scaled, sp);
  const MassScalingPlan& p = sim.mass_scaling();
  EXPECT_EQ(before.mass_scaling().bodies_scaled, 0);
  ASSERT_GT(p.bodies_scaled, 0);
  EXPECT_EQ(p.unscaled_step, before.stable_time_step());
  EXPECT_EQ(sim.stable_time_step(), p.time_step);
  EXPECT_GT(sim.stable_time_step(), 1.05 * before.stable_time_step());
  Real m0 = 0, m1 = 0;
  for (Index i = 0; i < sim.bodies().size(); ++i) {
    m0 += before.bodies().mass[i];
    m1 += sim.bodies().mass[i];
    // Mass and inertia by the same factor: the particle's inertia stays isotropic.
    EXPECT_NEAR(sim.bodies().inertia[i].x() / before.bodies().inertia[i].x(),
                sim.bodies().mass[i] / before.bodies().mass[i], 1e-12);
  }
  EXPECT_NEAR(m1 / m0, 1 + limit, 1e-12);
  const Real dt_crit = expect_estimate_brackets_critical_step(scaled, sp, sim);
  std::printf(
      "[selective mass scaling, +%.0f%% mass] %lld of %lld bodies up to %.3fx: estimate "
      "%.4g -> %.4g s (x%.3f), %.3f dt_crit\n",
      100 * limit, (long long)p.bodies_scaled, (long long)sim.bodies().size(), p.largest_factor,
      p.unscaled_step, p.time_step, p.time_step / p.unscaled_step, p.time_step / dt_crit);
}
