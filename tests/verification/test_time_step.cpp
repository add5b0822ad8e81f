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
#include <string>

#include "rcdem/core/error.hpp"
#include "rcdem/core/rng.hpp"
#include "rcdem/io/scenario.hpp"
#include "rcdem/solver/body_stiffness.hpp"
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

Scenario glued_box(Real size, Real alpha, Real inertia_scaling) {
  return test::elastic_box(
      size,
      fmt::format("dt_safety = 0.5\nparticle_rotational_inertia_scaling = {}\n", inertia_scaling) +
          test::glued_platens(),
      0.0, alpha);
}

// omega_max of M^-1 K, K the tangent stiffness assembled from the solver's own force routines.
Real highest_frequency(const Simulation& sim) {
  const Bodies& b = sim.bodies();
  const test::StaticModel model{&sim.specimen().contacts, b, sim.plates(), sim.plate_contacts(), 1};
  const Eigen::MatrixXd K = model.tangent_stiffness();
  Eigen::VectorXd w(K.rows());  // M^-1/2 (spheres: isotropic inertia)
  for (Index i = 0; i < b.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      w[6 * i + a] = 1.0 / std::sqrt(b.mass[i]);
      w[6 * i + 3 + a] = 1.0 / std::sqrt(b.inertia[i][a]);
    }
  const Eigen::MatrixXd A = w.asDiagonal() * (0.5 * (K + K.transpose())) * w.asDiagonal();
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues().maxCoeff());
}

// Steps with random small velocities; true if it ran `steps` steps without an instability.
bool runs_stably(Simulation& sim, Real dt, int steps) {
  sim.set_time_step(dt);
  Rng rng(7);
  Bodies& b = sim.bodies();
  for (Index i = 0; i < b.size(); ++i) {
    b.velocity[i] = 1e-4 * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    b.angular_velocity[i] = Vec3::Zero();
  }
  try {
    for (int s = 0; s < steps; ++s) sim.step();
  } catch (const Error&) {
    return false;
  }
  return true;
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
    const Real dt_crit = 2.0 / highest_frequency(sim);
    const Real est = sim.stable_time_step();
    EXPECT_GE(est, 0.5 * dt_crit * (1 - 1e-6));
    EXPECT_LE(est, dt_crit / std::sqrt(2.0) * (1 + 1e-6));
    EXPECT_LE(sim.time_step(), 0.36 * dt_crit);
    Simulation below(sc, sp), above(sc, sp);
    EXPECT_TRUE(runs_stably(below, 0.97 * dt_crit, 3000));
    EXPECT_FALSE(runs_stably(above, 1.05 * dt_crit, 3000));
    std::printf(
        "[time step, alpha %.1f, inertia x%.1f] %lld bodies: estimate %.4g s = %.3f dt_crit "
        "(dt_crit = 2 / omega_max = %.4g s); set by %s\n",
        c.alpha, c.inertia_scaling, (long long)sim.bodies().size(), est, est / dt_crit, dt_crit,
        sim.stable_time_step_limit().c_str());
  }
}
