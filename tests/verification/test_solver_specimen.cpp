// The solver on small generated specimens (SPEC 4-6): energy conservation without damping,
// homogeneous strain, stability at and beyond the reported time step, and a quasi-static tension
// test between glued plates checked against the specimen's own static solution.
//
// Specimens are 25-30 mm boxes (40-70 particles, 170-310 contacts) so that 10^4 steps take about
// a second. The contact law is EL throughout, so every expectation is elastic.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/laws/elastic.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/rng.hpp"
#include "rcdem/solver/plates.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/state/bodies.hpp"
#include "static_model.hpp"

using namespace rcdem;

namespace {

using test::elastic_box;

// Random velocities of about 1 mm/s and spins of about 1 mm/s over the radius: small enough that
// the motion stays linear (strains ~ 1e-7), large enough to load every contact.
void randomize_velocities(Bodies& b, std::uint64_t seed) {
  Rng rng(seed);
  auto vec = [&] { return Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)); };
  for (Index i = 0; i < b.size(); ++i) {
    b.velocity[i] = 1e-3 * vec();
    b.angular_velocity[i] = (1e-3 / b.radius[i]) * vec();
  }
}

// The kinetic part of the quantity leap-frog conserves for a linear system:
// 1/2 m v(n-1/2).v(n+1/2) (+ the rotational analogue).
Real leapfrog_kinetic(const Bodies& b, const std::vector<Vec3>& v_before,
                      const std::vector<Vec3>& w_before) {
  Real k = 0;
  for (Index i = 0; i < b.size(); ++i)
    k += 0.5 * b.mass[i] * v_before[i].dot(b.velocity[i]) +
         0.5 * w_before[i].dot(b.inertia[i].cwiseProduct(b.angular_velocity[i]));
  return k;
}

Vec3 momentum(const Bodies& b) {
  Vec3 p = Vec3::Zero();
  for (Index i = 0; i < b.size(); ++i) p += b.mass[i] * b.velocity[i];
  return p;
}

struct EnergyTrace {
  Real ledger_band = 0;    // (max - min) / first of the ledger's strain + kinetic
  Real leapfrog_band = 0;  // the same for strain + 1/2 m v(n-1/2).v(n+1/2)
  Real momentum_drift = 0;
  Real strain_mean = 0, kinetic_mean = 0;
  Real ledger_first_kinetic = 0, true_initial_kinetic = 0;
};

EnergyTrace run_undamped(Simulation& sim, int steps) {
  Bodies& b = sim.bodies();
  EnergyTrace t;
  for (Index i = 0; i < b.size(); ++i)
    t.true_initial_kinetic +=
        0.5 * b.mass[i] * b.velocity[i].squaredNorm() +
        0.5 * b.angular_velocity[i].dot(b.inertia[i].cwiseProduct(b.angular_velocity[i]));
  const Vec3 p0 = momentum(b);
  const Real p_scale = [&] {
    Real s = 0;
    for (Index i = 0; i < b.size(); ++i) s += b.mass[i] * b.velocity[i].norm();
    return s;
  }();
  Real l_min = 1e300, l_max = -1e300, f_min = 1e300, f_max = -1e300, l_first = 0, f_first = 0;
  std::vector<Vec3> v, w;
  for (int s = 0; s < steps; ++s) {
    v = b.velocity;
    w = b.angular_velocity;
    sim.step();
    const Energy& e = sim.energy();
    if (s == 0) {
      t.ledger_first_kinetic = e.kinetic;
      // The ledger's kinetic energy at step 0 averages in a zero "previous half step" (the run is
      // assumed to start at rest), so the ledger is compared from step 1 on.
    }
    const Real leap = e.strain + leapfrog_kinetic(b, v, w);
    if (s == 0) f_first = leap;
    f_min = std::min(f_min, leap);
    f_max = std::max(f_max, leap);
    if (s >= 1) {
      const Real ledger = e.strain + e.kinetic;
      if (s == 1) l_first = ledger;
      l_min = std::min(l_min, ledger);
      l_max = std::max(l_max, ledger);
      t.strain_mean += e.strain / (steps - 1);
      t.kinetic_mean += e.kinetic / (steps - 1);
    }
    for (Index i = 0; i < b.size(); ++i) {
      if (!b.position[i].allFinite() || !b.velocity[i].allFinite()) {
        ADD_FAILURE() << "non-finite state at step " << s;
        return t;
      }
    }
  }
  t.ledger_band = (l_max - l_min) / l_first;
  t.leapfrog_band = (f_max - f_min) / f_first;
  t.momentum_drift = (momentum(b) - p0).norm() / p_scale;
  return t;
}

}  // namespace

// 3. Energy. The dynamics conserve the leap-frog invariant (strain + 1/2 m v- . v+) to 1e-6 over
// 10^4 steps at the reported time step, and the linear momentum to rounding: the contact forces
// are conservative and equal and opposite, and the integrator is symplectic.
TEST(SolverSpecimen, UndampedElasticSpecimenConservesEnergyAndMomentum) {
  const Scenario sc = elastic_box(0.025);
  Simulation sim(sc, build_specimen(sc));
  ASSERT_TRUE(sim.plates().empty());
  ASSERT_GT(sim.specimen().particles.size(), 30);
  randomize_velocities(sim.bodies(), 11);
  const auto t0 = std::chrono::steady_clock::now();
  const EnergyTrace t = run_undamped(sim, 10000);
  const Real seconds = std::chrono::duration<Real>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(t.leapfrog_band, 1e-6);
  EXPECT_LT(t.momentum_drift, 1e-12);
  // Equipartition: about half the energy is strain energy on average.
  EXPECT_GT(t.strain_mean / (t.strain_mean + t.kinetic_mean), 0.35);
  EXPECT_LT(t.strain_mean / (t.strain_mean + t.kinetic_mean), 0.65);
  // The total matches what the bodies were given (the invariant differs from the kinetic energy
  // of the initial half-step velocities by O((omega dt)^2)).
  EXPECT_NEAR((t.strain_mean + t.kinetic_mean) / t.true_initial_kinetic, 1.0, 0.01);
  std::printf(
      "[undamped] %lld particles, %lld contacts, dt = %.4g s (stable estimate %.4g s): leap-frog "
      "invariant band %.3g, ledger strain+kinetic band %.3g, momentum drift %.3g; 10^4 steps in "
      "%.2f s\n",
      (long long)sim.specimen().particles.size(),
      (long long)sim.specimen().contacts.contact_count(), sim.time_step(), sim.stable_time_step(),
      t.leapfrog_band, t.ledger_band, t.momentum_drift, seconds);
}

// 3'. The acceptance criterion as the ledger reports it: Energy::strain + Energy::kinetic within
// 0.1% over 10^4 steps at the reported time step (dt_safety = 0.3).
//
// FAILS at present (band 0.56%): Energy::kinetic is the mean of the kinetic energies at the two
// half steps, 1/2 (K(n-1/2) + K(n+1/2)), which exceeds the leap-frog invariant's
// 1/2 m v(n-1/2).v(n+1/2) by 1/4 m |a dt|^2, i.e. by (omega dt)^2 / 2 of each mode's strain
// energy: an oscillation of O((omega dt)^2), not a drift, while the invariant itself holds to
// 1e-7 (test above). At dt_safety = 0.1 the ledger's band is 0.063%, at 0.5 1.5%.
TEST(SolverSpecimen, LedgerStrainPlusKineticWithinTenthOfAPercentAtReportedStep) {
  const Scenario sc = elastic_box(0.025);
  Simulation sim(sc, build_specimen(sc));
  randomize_velocities(sim.bodies(), 11);
  const EnergyTrace t = run_undamped(sim, 10000);
  EXPECT_LT(t.ledger_band, 1e-3) << "ledger strain + kinetic varies by " << t.ledger_band
                                 << " while strain + 1/2 m v-.v+ varies by " << t.leapfrog_band;
  // Starting from the given velocities the ledger's first kinetic energy should be about theirs;
  // it averages in K(-1/2) = 0 and reports about half (a run is assumed to start at rest).
  std::printf("[ledger] band %.3g; first-step kinetic / initial kinetic = %.3f\n", t.ledger_band,
              t.ledger_first_kinetic / t.true_initial_kinetic);
}

// 4. Homogeneous strain x = (I + eps) x0 (no rotation) gives every local point of a contact the
// same relative displacement eps d0 n0: u_n = (eps d0 n0) . n and u_s = eps d0 n0 - u_n n with n
// the current normal; to first order u_n = n0.eps.n0 d0 and |u_s| = |eps d0 n0 - u_n d0 n0|.
// The same with a finite rotation R on top (x = R (I + eps) x0, orientations R) gives the same
// u_n and |u_s| (objectivity).
TEST(SolverSpecimen, HomogeneousStrainGivesUniformContactStrains) {
  const Scenario sc = elastic_box(0.03);
  const Specimen sp = build_specimen(sc);
  const ContactNetwork& net = sp.contacts;
  Eigen::Matrix3d eps;
  eps << 1.0e-4, 0.3e-4, -0.2e-4,  //
      0.3e-4, -0.5e-4, 0.6e-4,     //
      -0.2e-4, 0.6e-4, 0.8e-4;
  const Real eps_norm = eps.norm();
  const Vec3 centre = 0.5 * (sp.geometry.lo + sp.geometry.hi);
  const Quat R(Eigen::AngleAxis<Real>(1.1, Vec3(0.3, -0.4, 0.87).normalized()));
  for (const bool rotated : {false, true}) {
    Bodies b = bodies_from_particles(sp.particles, 2400.0, 1.0);
    for (Index i = 0; i < b.size(); ++i) {
      const Vec3 strained =
          centre + (Eigen::Matrix3d::Identity() + eps) * (b.position0[i] - centre);
      b.position[i] = rotated ? Vec3(centre + R * (strained - centre)) : strained;
      b.orientation[i] = rotated ? R : Quat::Identity();
    }
    ContactState cs;
    cs.init(net, b.position0);
    evaluate_contacts(Elastic{}, net, b, cs, 1e-7);
    Real worst_exact = 0, worst_linear = 0, worst_force = 0;
    for (Index c = 0; c < net.contact_count(); ++c) {
      const Index a = net.particle_a[c], bb = net.particle_b[c];
      const Real d0 = net.distance0[c];
      const Vec3 n0 = (b.position0[bb] - b.position0[a]) / d0;
      ASSERT_NEAR((b.position0[bb] - b.position0[a]).norm(), d0, 1e-15);
      const Vec3 u = eps * n0 * d0;  // in the unrotated frame
      const Vec3 n = ((Eigen::Matrix3d::Identity() + eps) * n0).normalized();
      const Real un = u.dot(n);
      const Real us = (u - un * n).norm();
      const Real un_lin = n0.dot(eps * n0) * d0;
      const Real us_lin = (u - un_lin * n0).norm();
      const Real scale = eps_norm * d0;
      Vec3 f = Vec3::Zero();
      for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
        const LocalPointState& s = cs.point[m];
        worst_exact = std::max(
            {worst_exact, std::abs(s.un - un) / scale, std::abs(s.us.norm() - us) / scale});
        worst_linear = std::max({worst_linear, std::abs(s.un - un_lin) / scale,
                                 std::abs(s.us.norm() - us_lin) / scale});
        const LocalPointConstants& k = net.constants[m];
        EXPECT_EQ(s.fn, k.kn * s.un);
        f += -s.fn * cs.normal[c] + cs.shear_force(c, m);
      }
      worst_force = std::max(worst_force, (cs.force_b[c] - f).norm() / (f.norm() + 1e-300));
    }
    EXPECT_LT(worst_exact, 1e-9);
    EXPECT_LT(worst_linear, 2 * eps_norm);  // second-order terms only
    EXPECT_LT(worst_force, 1e-12);
    std::printf(
        "[homogeneous strain%s] %lld contacts: worst |error| / (|eps| d0): exact %.3g, "
        "first order %.3g (|eps| = %.3g)\n",
        rotated ? ", rotated 63 deg" : "", (long long)net.contact_count(), worst_exact,
        worst_linear, eps_norm);
  }
}

// 5a. At the reported time step an elastic specimen with random velocities stays finite and
// bounded for 2000 steps.
TEST(SolverSpecimen, StableAtReportedTimeStep) {
  const Scenario sc = elastic_box(0.025);
  Simulation sim(sc, build_specimen(sc));
  EXPECT_NEAR(sim.time_step(), sc.solver.dt_safety * sim.stable_time_step(), 1e-20);
  randomize_velocities(sim.bodies(), 5);
  const EnergyTrace t = run_undamped(sim, 2000);
  EXPECT_LT(t.leapfrog_band, 1e-6);
  Real worst = 0;
  const Bodies& b = sim.bodies();
  for (Index i = 0; i < b.size(); ++i) {
    ASSERT_TRUE(b.position[i].allFinite());
    worst = std::max(worst, (b.position[i] - b.position0[i]).norm());
  }
  // Moving at ~1 mm/s for 2000 steps of ~0.1 us covers ~0.2 um: nothing runs away.
  EXPECT_LT(worst, 1e-5);
}

// 5b. At 4x the stable estimate, stepping stops with rcdem::Error naming the instability (not a
// silent NaN), within a few steps.
TEST(SolverSpecimen, FourTimesStableStepThrowsInstability) {
  const Scenario sc = elastic_box(0.025);
  Simulation sim(sc, build_specimen(sc));
  sim.set_time_step(4 * sim.stable_time_step());
  randomize_velocities(sim.bodies(), 5);
  int steps = 0;
  std::string message;
  try {
    for (; steps < 2000; ++steps) sim.step();
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_LT(steps, 2000) << "no error in 2000 steps at 4x the stable estimate";
  EXPECT_NE(message.find("instability"), std::string::npos) << message;
  for (const Vec3& x : sim.bodies().position) EXPECT_TRUE(x.allFinite());
  std::printf("[4x stable step] threw after %d steps: %s\n", steps, message.c_str());
}

// 5c. With k_s = alpha k_n > k_n the shear springs are the stiffer ones: an estimate that summed
// k_n only once let this accepted scenario (alpha = 30, dt_safety 0.5) blow up at step 11. The
// body blocks carry k_s across every normal (test_time_step.cpp checks them against the
// assembly's eigenvalues).
TEST(SolverSpecimen, StableEstimateCoversShearSprings) {
  const Scenario sc = parse_scenario(R"(
[specimen]
shape = "box"
size = [0.025, 0.025, 0.025]
[generation]
seed = 3
relaxation_iterations = 100
[contact]
law = "EL"
alpha = 30.0
[solver]
damping = 0.0
dt_safety = 0.5
)",
                                     "stiff_shear.toml");
  Simulation sim(sc, build_specimen(sc));
  randomize_velocities(sim.bodies(), 5);
  int steps = 0;
  try {
    for (; steps < 1000; ++steps) sim.step();
  } catch (const Error& e) {
    ADD_FAILURE() << "after " << steps << " steps: " << e.what();
  }
  EXPECT_EQ(steps, 1000);
}

// 6. A 30 mm elastic cube between a fixed glued bottom plate and a glued top plate pulled up
// (tension), with the default local damping 0.7: loaded over ~40 wave transits, then held. At the
// end the bottom reaction is minus the top one, the energy ledger balances, the stored energy is
// half the reaction times the displacement (Clapeyron), and the reaction equals the static
// solution K q = f of the specimen's own contacts and plate springs, K assembled by central
// differences of the same force routines.
//
// With selective mass scaling (`added_mass_limit`, solver/selective_mass_scaling.hpp) the same
// holds at the same number of steps: the heavier bodies change the path, not the static answer.
static void glued_plate_tension_reaches_static_solution(Real added_mass_limit) {
  const Real size = 0.03, strain = 1e-4;
  const auto scenario = [&](Real v, Real ramp) {
    return elastic_box(size,
                       fmt::format("added_mass_limit = {}\n", added_mass_limit) +
                           test::glued_platens(fmt::format(
                               "velocity = {}\nramp_time = {}\n[loading]\ncontrol_plate = "
                               "\"top\"\n",
                               v, ramp)),
                       0.7);
  };
  const Specimen sp = build_specimen(scenario(1.0, 0.0));
  // The plate springs count in the stable estimate: the time step comes from the plated specimen.
  const Real dt = Simulation(scenario(1.0, 0.0), sp).time_step();
  const int load_steps = 3000, hold_steps = 1500;
  const Real ramp = 0.3 * load_steps * dt;
  const Real delta = strain * size;
  // The cosine ramp covers half its duration's worth of displacement.
  const Real v = delta / (load_steps * dt - 0.5 * ramp);
  const Scenario sc = scenario(v, ramp);
  Simulation sim(sc, sp);
  ASSERT_EQ(sim.time_step(), dt);
  ASSERT_EQ(sim.plates().size(), 2u);
  ASSERT_EQ(sim.plates()[1].name, "top");
  test::StaticModel model{&sim.specimen().contacts, sim.bodies(), sim.plates(),
                          sim.plate_contacts(), 1};

  Plate& top = sim.plates()[1];
  const Plate& bottom = sim.plates()[0];
  Real reaction_mismatch_at_load_end = 0;
  for (int s = 0; s < load_steps + hold_steps; ++s) {
    if (s == load_steps) {
      EXPECT_NEAR(top.displacement / delta, 1.0, 1e-3);
      reaction_mismatch_at_load_end =
          std::abs(top.force.z() + bottom.force.z()) / std::abs(top.force.z());
      top.set_velocity(0.0);  // hold
    }
    sim.step();
  }
  const Real u = top.displacement;
  const Real F = top.load();
  const Energy& e = sim.energy();
  EXPECT_GT(F, 0.0);
  EXPECT_NEAR(-top.force.z() / F, 1.0, 1e-15);  // tension: the specimen pulls the plate down
  EXPECT_LT(std::abs(top.force.z() + bottom.force.z()), 0.01 * F);
  EXPECT_LT(reaction_mismatch_at_load_end, 0.01);  // quasi-static already while loading
  EXPECT_LT(e.balance_error(), 0.01);
  EXPECT_NEAR(e.external_work / (e.strain + e.kinetic + e.dissipated()), 1.0, 0.01);
  EXPECT_LT(e.kinetic, 1e-6 * e.strain);
  // Clapeyron (linear elasticity); the geometric nonlinearity is O(strain) = 1e-4.
  EXPECT_NEAR(e.strain / (0.5 * F * u), 1.0, 10 * strain);

  // The static solution.
  const Eigen::MatrixXd K = model.tangent_stiffness();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(K.rows());
  const Real asymmetry = (K - K.transpose()).norm() / K.norm();
  const Eigen::VectorXd q = K.partialPivLu().solve(model.forces(zero, u));
  Real reaction_static = 0;
  const Eigen::VectorXd residual = model.forces(q, u, &reaction_static);
  // K is the tangent at q = 0; the residual at q is the geometric nonlinearity, O(strain).
  EXPECT_LT(residual.norm(), 10 * strain * model.forces(zero, u).norm());
  EXPECT_NEAR(top.force.z() / reaction_static, 1.0, 10 * strain);
  Real worst_position = 0;
  for (Index i = 0; i < sim.bodies().size(); ++i)
    worst_position = std::max(
        worst_position,
        (sim.bodies().position[i] - sim.bodies().position0[i] - q.segment<3>(6 * i)).norm());
  EXPECT_LT(worst_position, 10 * strain * u);
  // The macroscopic modulus, loosely: Table 2's E_bar = 48.7 GPa gives E = 34.2 GPa in the paper.
  const Real E = (F / (size * size)) / (u / size);
  EXPECT_GT(E / 48.7e9, 0.4);
  EXPECT_LT(E / 48.7e9, 0.9);
  std::printf(
      "[glued tension] %lld particles, %lld plate contacts: F = %.5g N at u = %.4g m; static "
      "F = %.5g N (ratio - 1 = %.3g); |F_top + F_bottom| / F = %.3g (end of loading %.3g); balance "
      "error %.3g; strain / (F u / 2) = %.6f; worst |x - x_static| / u = %.3g; K asymmetry %.3g; "
      "E = %.4g GPa (%.3f E_bar)\n",
      (long long)sim.bodies().size(), (long long)sim.plate_contacts().size(), F, u,
      -reaction_static, top.force.z() / reaction_static - 1,
      std::abs(top.force.z() + bottom.force.z()) / F, reaction_mismatch_at_load_end,
      e.balance_error(), e.strain / (0.5 * F * u), worst_position / u, asymmetry, E / 1e9,
      E / 48.7e9);
}

TEST(SolverSpecimen, GluedPlateTensionReachesStaticSolution) {
  glued_plate_tension_reaches_static_solution(0.0);
}

TEST(SolverSpecimen, GluedPlateTensionWithSelectiveMassScalingReachesStaticSolution) {
  glued_plate_tension_reaches_static_solution(0.05);
}
