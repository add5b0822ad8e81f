// Intact contacts evaluated from their sums (contact/elastic_condensation.hpp) against the same
// contacts visited point by point: the force and both torques of every contact for random
// kinematics (the algebra), the bound that sends a contact back to its points, and whole runs
// through damage with the condensation on and off (the catch-up of stale histories, checkpoints'
// view of the state).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/contact/laws/bilinear_softening.hpp"
#include "rcdem/core/rng.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

using namespace rcdem;

namespace {

// A 40 mm cube of the calibrated concrete (Table 2 parameters), between glued plates: the top one
// pulled up (tension) or pushed down (compression).
Scenario bl_cube(Real velocity, bool condense, const std::string& extra = "") {
  return parse_scenario(fmt::format(R"(
[specimen]
shape = "box"
size = [0.04, 0.04, 0.04]
[generation]
seed = 5
relaxation_iterations = 100
[contact]
E_bar = 48.7e9
alpha = 0.3
mu_c = 0.50
sigma_nt = 4.15e6
tau = 21.0e6
G_fn = 9.002
G_fs = 2380.785
[solver]
damping = 0.7
condense_elastic_contacts = {1}
[plates.bottom]
face = "z-"
glued = true
[plates.top]
face = "z+"
velocity = {0}
ramp_time = 2.0e-5
glued = true
[loading]
control_plate = "top"
{2}
)",
                                    velocity, condense ? "true" : "false", extra),
                        "bl_cube.toml");
}

BilinearSoftening law_of(const Scenario& sc) {
  return {sc.contact.sigma_nt, sc.contact.tau, sc.contact.G_fn, sc.contact.G_fs, sc.contact.mu_c};
}

// Every body moved and turned at random: translations `move` (m) and rotations `turn` (rad).
Bodies displaced(const Specimen& sp, Real move, Real turn, std::uint64_t seed) {
  Bodies b = bodies_from_particles(sp.particles, 2400.0, 1.0);
  Rng rng(seed);
  auto vec = [&] { return Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)); };
  for (Index i = 0; i < b.size(); ++i) {
    b.position[i] = b.position0[i] + move * vec();
    const Vec3 r = turn * vec();
    b.orientation[i] = Quat(Eigen::AngleAxis<Real>(r.norm(), r.normalized()));
    b.angular_velocity[i] = vec();
  }
  return b;
}

struct Evaluated {
  ContactState cs;
  ElasticCondensation cond;
};

Evaluated evaluate(const BilinearSoftening& law, const Specimen& sp, const Bodies& b,
                   bool condense) {
  Evaluated e;
  e.cs.init(sp.contacts, b.position0);
  std::vector<Eigen::Matrix3d> rot;
  for (const Quat& q : b.orientation) rot.push_back(q.toRotationMatrix());
  const BodyPoses pose = BodyPoses::of(b.position, b.orientation);
  const ContactInputs in{sp.contacts,
                         b.position.data(),
                         b.position0.data(),
                         b.angular_velocity.data(),
                         b.orientation0.data(),
                         rot.data(),
                         nullptr,
                         1e-7,
                         pose.ptr()};
  if (condense) {
    e.cond = ElasticCondensation::build(sp.contacts, b.position0);
    evaluate_contacts(law, in, e.cs, &e.cond, &in);
  } else {
    evaluate_contacts(law, in, e.cs);
  }
  return e;
}

Real largest(const std::vector<Vec3>& v) {
  Real m = 0;
  for (const Vec3& x : v) m = std::max(m, x.norm());
  return m;
}

// What separates two correct evaluations of a contact: u0 = (x_B - x_A) - R_B (x_B0 - x_A0) is a
// difference of millimetre vectors, rounded to a few ulp of |x_B - x_A| (about 1e-18 m here) in
// either evaluation, and each path rounds it its own way (fused or separate multiply-adds). So a
// contact's force may differ by K_c x 8 eps |dx| (K_c = sum kn), its torques by that times 2 |dx|.
struct ContactTolerance {
  Real force, torque;
};
ContactTolerance rounding_of_u0(const Specimen& sp, const Bodies& b, Index c) {
  const ContactNetwork& net = sp.contacts;
  Real k = 0;
  for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) k += net.constants[m].kn;
  const Real dx = (b.position[net.particle_b[c]] - b.position[net.particle_a[c]]).norm();
  const Real f = k * 8 * std::numeric_limits<Real>::epsilon() * dx;
  return {f, f * 2 * dx};
}

Index worse_than_rounding(const Specimen& sp, const Bodies& b, const ContactState& x,
                          const ContactState& y, const std::vector<std::uint8_t>* only = nullptr) {
  Index n = 0;
  for (Index c = 0; c < sp.contacts.contact_count(); ++c) {
    if (only && !(*only)[c]) continue;
    const ContactTolerance tol = rounding_of_u0(sp, b, c);
    n += (x.force_b[c] - y.force_b[c]).norm() > tol.force ||
         (x.torque_a[c] - y.torque_a[c]).norm() > tol.torque ||
         (x.torque_b[c] - y.torque_b[c]).norm() > tol.torque;
  }
  return n;
}

}  // namespace

// The algebra: for displacements of 1e-8 m and rotations of 1e-6 rad (well inside the elastic
// range) every contact is condensed, and its force and torques equal the point loop's to the
// rounding of u0 (above); with rotations of 1e-12 rad, where u0's rounding is the same in both,
// to 1e-13 of the largest.
TEST(ElasticCondensation, CondensedContactGivesItsPointsForceAndTorques) {
  const Scenario sc = bl_cube(0.0, true);
  const Specimen sp = build_specimen(sc);
  const BilinearSoftening law = law_of(sc);
  const Index nc = sp.contacts.contact_count();
  ASSERT_GT(nc, 500);
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const Bodies b = displaced(sp, 1e-8, 1e-6, seed);
    const Evaluated full = evaluate(law, sp, b, false);
    const Evaluated fast = evaluate(law, sp, b, true);
    EXPECT_EQ(fast.cond.condensed_count(), nc) << "every contact is far from its limits";
    EXPECT_EQ(worse_than_rounding(sp, b, full.cs, fast.cs), 0);
  }
  const Bodies b = displaced(sp, 1e-8, 1e-12, 4);
  const Evaluated full = evaluate(law, sp, b, false);
  const Evaluated fast = evaluate(law, sp, b, true);
  const Real f_scale = largest(full.cs.force_b);
  const Real t_scale = std::max(largest(full.cs.torque_a), largest(full.cs.torque_b));
  Real worst_f = 0, worst_t = 0;
  for (Index c = 0; c < nc; ++c) {
    worst_f = std::max(worst_f, (fast.cs.force_b[c] - full.cs.force_b[c]).norm() / f_scale);
    worst_t = std::max(worst_t, (fast.cs.torque_a[c] - full.cs.torque_a[c]).norm() / t_scale);
    worst_t = std::max(worst_t, (fast.cs.torque_b[c] - full.cs.torque_b[c]).norm() / t_scale);
  }
  EXPECT_LT(worst_f, 1e-13);
  EXPECT_LT(worst_t, 1e-13);
}

// The identity the bound rests on: D = R_B - R_A, a difference of two rotations, has singular
// values 2 sin(phi / 2) (twice) and 0, phi the angle of R_A^T R_B, so |D rho| <= |D|_2 |rho| with
// |D|_2^2 = |D|_F^2 / 2 exactly, for small and large relative turns alike.
TEST(ElasticCondensation, DifferenceOfTwoRotationsHasHalfItsFrobeniusNormSquared) {
  Rng rng(11);
  const auto random_rotation = [&](Real max_angle) {
    const Vec3 axis = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)).normalized();
    return Eigen::Matrix3d(Eigen::AngleAxis<Real>(rng.uniform(0, max_angle), axis));
  };
  for (const Real scale : {1e-6, 1e-3, 0.3, 3.0}) {
    for (int k = 0; k < 50; ++k) {
      const Eigen::Matrix3d ra = random_rotation(3.0);
      const Eigen::Matrix3d rb = ra * random_rotation(scale);
      const Eigen::Matrix3d d = rb - ra;
      const Real phi = Eigen::AngleAxis<Real>(ra.transpose() * rb).angle();
      const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix3d>(d).singularValues();
      // D's entries are differences of entries <= 1: each carries ~1e-16 of absolute rounding.
      const Real expected = 2 * std::sin(0.5 * phi), tol = 1e-14 + 1e-12 * expected;
      EXPECT_NEAR(sv[0], expected, tol) << scale;
      EXPECT_NEAR(sv[1], expected, tol) << scale;
      EXPECT_LT(sv[2], 1e-14) << scale;
      EXPECT_NEAR(d.squaredNorm(), 2 * expected * expected, 4 * expected * tol) << scale;
    }
  }
}

// The bound: with rotations large enough to open some points past their limits the contacts near
// them are not condensed; whichever path each contact takes, the forces equal the point loop's,
// and no condensed contact has a point past a limit.
TEST(ElasticCondensation, ContactsNearTheirLimitsGoThroughTheirPoints) {
  const Scenario sc = bl_cube(0.0, true);
  const Specimen sp = build_specimen(sc);
  const BilinearSoftening law = law_of(sc);
  const Index nc = sp.contacts.contact_count();
  // sigma_nt / E_bar = 8.5e-5: rotations of 1e-4 rad over the particles' ~2 mm reach ~2e-7 m,
  // near the elastic limit of a ~2.5 mm contact (~2e-7 m).
  const Bodies b = displaced(sp, 1e-8, 1e-4, 7);
  const Evaluated full = evaluate(law, sp, b, false);
  const Evaluated fast = evaluate(law, sp, b, true);
  const Index condensed = fast.cond.condensed_count();
  EXPECT_GT(condensed, nc / 20);
  EXPECT_LT(condensed, nc);
  Index damaged_in_condensed = 0;
  for (Index c = 0; c < nc; ++c)
    if (fast.cond.condensed[c])
      for (Index m = sp.contacts.point_begin[c]; m < sp.contacts.point_begin[c + 1]; ++m)
        damaged_in_condensed += full.cs.point[m].damage > 0;
  EXPECT_EQ(damaged_in_condensed, 0);
  Index damaged = 0;
  for (const LocalPointRecord& r : full.cs.point.records) damaged += r.history.damage > 0;
  EXPECT_GT(damaged, 0) << "the kinematics reach some limits";
  EXPECT_EQ(worse_than_rounding(sp, b, full.cs, fast.cs), 0);
  std::printf("[bound] %lld of %lld contacts condensed, %lld points damaged\n",
              (long long)condensed, (long long)nc, (long long)damaged);
}

namespace {

// A run's loads, step by step, and what it ended with.
struct Trace {
  std::vector<Real> load;
  std::int64_t first_damage_step = -1;  // the first step with dissipation by damage
  Index condensed_max = 0, condensed_end = 0, broken = 0, damaged = 0;
  Real damage = 0, friction = 0, strain = 0;
};

// `read_every` > 0: read the state (as history rows and checkpoints do) every that many steps.
Trace run(const Scenario& sc, int steps, int read_every = 0) {
  Simulation sim(sc, build_specimen(sc));
  Trace t;
  for (int s = 1; s <= steps; ++s) {
    sim.step();
    t.load.push_back(-sim.plates()[1].force.z());
    if (t.first_damage_step < 0 && sim.ledger().damage > 0) t.first_damage_step = s;
    t.condensed_max = std::max(t.condensed_max, sim.condensed_contacts());
    if (read_every > 0 && s % read_every == 0) {
      (void)sim.contacts();
      (void)sim.strain_energy();
    }
  }
  t.condensed_end = sim.condensed_contacts();
  t.broken = sim.broken_points();
  t.damaged = sim.damaged_points();
  t.damage = sim.ledger().damage;
  t.friction = sim.ledger().friction;
  t.strain = sim.strain_energy();
  return t;
}

Real worst_difference(const Trace& x, const Trace& y, std::size_t from, std::size_t to) {
  Real w = 0;
  for (std::size_t s = from; s < to; ++s) w = std::max(w, std::abs(x.load[s] - y.load[s]));
  return w;
}

Real peak(const Trace& t) {
  Real p = 0;
  for (Real l : t.load) p = std::max(p, std::abs(l));
  return p;
}

}  // namespace

// Reading the state mid-run (Simulation::contacts() brings condensed contacts' histories up to
// date, as every history row and checkpoint does) changes nothing that follows: the same loads,
// bit for bit, through cracking.
TEST(ElasticCondensation, ReadingTheStateChangesNothingThatFollows) {
  const Scenario sc = bl_cube(0.02, true);
  const Trace quiet = run(sc, 4000);
  const Trace read = run(sc, 4000, 7);
  ASSERT_GT(quiet.broken, 0) << "the run reaches cracking";
  for (std::size_t s = 0; s < quiet.load.size(); ++s)
    ASSERT_EQ(quiet.load[s], read.load[s]) << "step " << s + 1;
  EXPECT_EQ(quiet.damage, read.damage);
  EXPECT_EQ(quiet.broken, read.broken);
}

// The strain energy of condensed contacts from their sums (condensed_strain_energy, what a history
// row reads) equals their points' energy once their histories are brought up to date, before and
// after cracking, in tension and in compression.
TEST(ElasticCondensation, StrainEnergyFromTheSumsEqualsThePoints) {
  for (const Real velocity : {0.02, -0.05}) {
    const Scenario sc = bl_cube(velocity, true);
    Simulation sim(sc, build_specimen(sc));
    int checked = 0;
    for (int s = 1; s <= 4000; ++s) {
      sim.step();
      if (s % 500 != 0) continue;
      const Index condensed = sim.condensed_contacts();
      ASSERT_GT(condensed, 0) << "some contacts are condensed at step " << s;
      const Real from_sums = sim.strain_energy();
      (void)sim.contacts();  // the catch-up: every point's history current
      ASSERT_EQ(sim.condensed_contacts(), 0);
      const Real from_points = sim.strain_energy();
      ASSERT_GT(from_points, 0);
      EXPECT_NEAR(from_sums, from_points, 1e-12 * from_points)
          << "velocity " << velocity << ", step " << s << ", " << condensed << " condensed";
      ++checked;
    }
    EXPECT_EQ(checked, 8);
    EXPECT_GT(sim.damaged_points() + sim.broken_points(), 0) << "velocity " << velocity;
  }
}

// Whole runs, condensation on and off, through the peak and into softening, in tension and in
// compression (friction and shear caps). The two differ by rounding at first (the sums are taken
// in another order), and the local damping's sign(v) (Cundall) amplifies any rounding difference
// exponentially (measured: 1e-17 m at step 100, 5e-14 m at step 600), as does cracking later. So
// the measure is the spread of the point loop itself under perturbations at rounding level (the
// plate's speed x (1 + e), e = +-1e-12, +-2e-12, +-3e-12): the condensed run stays within 2x the
// largest of them, in the load at every step and in the energy dissipated by damage. The
// condensation is used at first and left where the cube cracks.
namespace {
void expect_run_matches_point_loop(Real velocity, int steps, const char* name) {
  const Trace on = run(bl_cube(velocity, true), steps);
  const Trace off = run(bl_cube(velocity, false), steps);
  std::vector<Trace> nudged;
  for (const Real e : {1e-12, -1e-12, 2e-12, -2e-12, 3e-12, -3e-12})
    nudged.push_back(run(bl_cube(velocity * (1 + e), false), steps));
  const Index nc = build_specimen(bl_cube(velocity, true)).contacts.contact_count();
  ASSERT_GT(off.first_damage_step, 10) << name;
  ASSERT_GT(off.broken + off.damaged, 50) << name << ": the cube is damaged";
  const auto first = static_cast<std::size_t>(off.first_damage_step);
  const Real p = peak(off);
  const Real before = worst_difference(on, off, 0, first - 1);
  Real spread_before = 0, spread = 0, spread_damage = 0;
  for (const Trace& t : nudged) {
    spread_before = std::max(spread_before, worst_difference(t, off, 0, first - 1));
    spread = std::max(spread, worst_difference(t, off, 0, off.load.size()));
    spread_damage = std::max(spread_damage, std::abs(t.damage - off.damage));
  }
  const Real after = worst_difference(on, off, 0, on.load.size());
  EXPECT_LT(after, 2 * spread + 1e-9 * p) << name;
  EXPECT_LE(std::abs(on.damage - off.damage), 2 * spread_damage + 1e-9 * off.damage) << name;
  EXPECT_EQ(on.condensed_max, nc) << name << ": every contact is condensed at first";
  EXPECT_LT(on.condensed_end, nc) << name << ": damage sends contacts back to their points";
  std::printf(
      "[%s] %lld contacts, %lld condensed at the end; peak %.5g N; worst load difference "
      "on/off %.3g N before the first damage (step %lld), %.3g N over the run; point loop nudged "
      "by 1e-12: %.3g / %.3g N; damage energy on %.6g / off %.6g J (nudged: within %.3g J); "
      "broken points "
      "%lld / %lld\n",
      name, (long long)nc, (long long)on.condensed_end, p, before, (long long)first, after,
      spread_before, spread, on.damage, off.damage, spread_damage, (long long)on.broken,
      (long long)off.broken);
}
}  // namespace

TEST(ElasticCondensation, TensionRunMatchesThePointLoopThroughDamage) {
  expect_run_matches_point_loop(0.02, 6000, "tension");
}

TEST(ElasticCondensation, CompressionRunMatchesThePointLoopThroughDamage) {
  expect_run_matches_point_loop(-0.05, 5000, "compression");
}
