// Damaged contacts held to their sums (contact/held_contacts.hpp, solver.hold_unloading_contacts):
// a box pulled apart through its peak and softening gives the same plate force, damage and
// energies with and without holding, to rounding; the energy of the held contacts from their sums
// equals their points' once caught up; reads and checkpoints change nothing; the energy kept by
// the step equals the one summed after it to the bit; each held contact's force, moments and
// dissipation are its points'; the held run is the same bits at 1 and 2 threads and after a
// restart; and intact contacts near their limits are held only with solver.hold_intact_contacts.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
#include "rcdem/contact/held_contacts.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/solver/concrete_contacts.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/state/body_poses.hpp"
#include "small_scenarios.hpp"

using namespace rcdem;
namespace fs = std::filesystem;

namespace {

// The pulled box (small_scenarios.hpp) at the speed `velocity`: slow enough that most of its
// damaged contacts unload elastically once the crack has formed. Held: as by default, softening
// contacts too (solver.hold_softening_contacts).
Scenario pulled_box(bool hold, Real velocity = 0.05) {
  return test::pulled_box(
      "BL", hold ? "" : "hold_unloading_contacts = false", velocity);
}

constexpr int kSteps = 4000;  // through the peak (about step 1,500) and well into the softening

Real load(const Simulation& sim) { return -sim.find_plate("top")->force.z(); }

void set_threads(int n) {
#if defined(_OPENMP)
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

// What a run gives at every step.
struct Trace {
  std::vector<Real> load, energy;
  Real damage = 0;  // dissipated by damage at the end
  Index most_held = 0;
};

Trace run(const Scenario& sc) {
  Simulation sim(sc, build_specimen(sc));
  Trace t;
  for (int k = 0; k < kSteps; ++k) {
    sim.step();
    t.load.push_back(load(sim));
    t.energy.push_back(sim.strain_energy());
    t.most_held = std::max(t.most_held, sim.held_contacts());
  }
  t.damage = sim.ledger().damage;
  return t;
}

Real worst(const std::vector<Real>& a, const std::vector<Real>& b) {
  Real w = 0;
  for (std::size_t k = 0; k < a.size(); ++k) w = std::max(w, std::abs(a[k] - b[k]));
  return w;
}

}  // namespace

// Held and visited runs differ by rounding at first (sums in another order, one elastic update for
// several in the catch-up), and cracking amplifies any rounding difference (as for the intact
// condensation, test_elastic_condensation.cpp). So the measure is the spread of the visited run
// itself under perturbations at rounding level (the plate's speed x (1 + e), e = +-1e-12,
// +-2e-12, +-3e-12): the held run stays within 2x the largest of them, in the load and strain
// energy at every step and in the energy dissipated by damage.
TEST(HeldContacts, SameResultsAsVisitingThePointsToRounding) {
  const Trace held = run(pulled_box(true)), visited = run(pulled_box(false));
  Real spread_load = 0, spread_energy = 0, spread_damage = 0;
  for (const Real e : {1e-12, -1e-12, 2e-12, -2e-12, 3e-12, -3e-12}) {
    const Trace t = run(pulled_box(false, 0.05 * (1 + e)));
    spread_load = std::max(spread_load, worst(t.load, visited.load));
    spread_energy = std::max(spread_energy, worst(t.energy, visited.energy));
    spread_damage = std::max(spread_damage, std::abs(t.damage - visited.damage));
  }
  const Real peak = *std::max_element(visited.load.begin(), visited.load.end());
  EXPECT_LT(visited.load.back(), 0.5 * peak) << "the box must be well past its peak";
  EXPECT_GT(held.most_held, 50) << "the test must hold contacts";
  EXPECT_EQ(visited.most_held, 0);
  EXPECT_LT(worst(held.load, visited.load), 2 * spread_load + 1e-9 * peak);
  EXPECT_LT(worst(held.energy, visited.energy), 2 * spread_energy + 1e-9 * visited.energy.back());
  EXPECT_LE(std::abs(held.damage - visited.damage), 2 * spread_damage + 1e-9 * visited.damage);
  std::printf(
      "peak %.6g N; worst load difference held/visited %.3g N, nudged %.3g N; damage "
      "energy held %.8g / visited %.8g J (nudged: within %.3g J); most held %lld\n",
      peak, worst(held.load, visited.load), spread_load, held.damage, visited.damage, spread_damage,
      static_cast<long long>(held.most_held));
}

// The simulation's concrete contacts (null if it has none).
const ConcreteContacts* concrete_part(const Simulation& sim) {
  for (const StepPart* part : sim.parts())
    if (const auto* concrete = dynamic_cast<const ConcreteContacts*>(part)) return concrete;
  return nullptr;
}

// The concrete contacts' strain energy as the run sums it (a held contact's from its sums).
Real concrete_strain_energy(const Simulation& sim) {
  Real e = 0;
  concrete_part(sim)->add_strain_energy(e);
  return e;
}

// ... and from every contact's points (a held one's as a read caught them up).
Real points_strain_energy(const Scenario& sc, const Simulation& sim) {
  const ContactState& cs = sim.contacts();
  const ContactNetwork& net = sim.specimen().contacts;
  Real e = 0;
  std::visit(
      [&](const auto& law) {
        for (Index c = 0; c < net.contact_count(); ++c) e += cs.strain_energy(law, net, c);
      },
      make_contact_law(sc.law, sc.contact));
  return e;
}

// The held contacts' strain energy from their sums (Simulation::strain_energy) equals their points'
// energy once a read has brought them up to date (contacts(), which keeps them held).
TEST(HeldContacts, EnergyFromTheSumsEqualsThePointsCaughtUp) {
  const Scenario sc = pulled_box(true);
  Simulation sim(sc, build_specimen(sc));
  Index checked = 0;
  for (int k = 1; k <= kSteps; ++k) {
    sim.step();
    const Index held = sim.held_contacts();
    if (k % 250 != 0 || held == 0) continue;
    const Real from_points = points_strain_energy(sc, sim);  // the read: condensed ones current
    const Real from_sums = concrete_strain_energy(sim);      // the held ones from their sums
    EXPECT_EQ(sim.held_contacts(), held) << "a read keeps the held contacts";
    EXPECT_NEAR(from_points, from_sums, 1e-11 * from_sums) << "step " << k;
    ++checked;
  }
  EXPECT_GT(checked, 5);
}

// Reading the points (snapshots, checkpoints) changes nothing a run computes: a run read every few
// steps, and checkpointed now and then, gives the same bits at every step as one never read.
TEST(HeldContacts, ReadsAndCheckpointsDoNotChangeTheRun) {
  const Scenario sc = pulled_box(true);
  Simulation quiet(sc, build_specimen(sc)), read(sc, build_specimen(sc));
  const fs::path dir =
      fs::temp_directory_path() / ("rcdem_held_reads_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Index held_at_reads = 0;
  for (int k = 1; k <= kSteps; ++k) {
    quiet.step();
    read.step();
    ASSERT_EQ(load(quiet), load(read)) << "step " << k;
    // Before this step's reads: after one, the condensed contacts' energy comes from their points
    // caught up, not from their sums (the same to rounding), as a run's history row never reads it.
    ASSERT_EQ(quiet.strain_energy(), read.strain_energy()) << "step " << k;
    if (k % 7 == 0) {
      const Index held = read.held_contacts();
      (void)read.contacts();
      if (k % 14 == 0) (void)read.contacts();  // twice between two steps
      ASSERT_EQ(read.held_contacts(), held);
      held_at_reads += held;
    }
    if (k % 500 == 0)
      io::write_checkpoint(dir, io::CheckpointParts{&read, nullptr, nullptr, nullptr}, 0);
  }
  EXPECT_EQ(quiet.ledger().damage, read.ledger().damage);
  EXPECT_GT(held_at_reads, 1000) << "the reads must meet held contacts";
  fs::remove_all(dir);
}

// Intact contacts near their elastic limits (solver.hold_intact_contacts, on by default): the
// condensation's bound (total displacement, whole-rotation spread) sends them to their points, and
// the held contacts' bound (each point's room at entry, the change since then row by row) holds
// them. So the pulled box holds a contact before any point is damaged, and intact contacts are
// among the held ones over its first half, only with the key on. (That they stay below their
// limits while held: NoHeldPointLeavesItsRoom, which checks every held contact's points, intact
// ones too.)
TEST(HeldContacts, IntactContactsNearTheirLimitsAreHeldOnlyWithTheKey) {
  for (const bool on : {true, false}) {
    const Scenario sc = test::pulled_box("BL", on ? "" : "hold_intact_contacts = false", 0.05);
    Simulation sim(sc, build_specimen(sc));
    const ConcreteContacts* concrete = concrete_part(sim);
    ASSERT_NE(concrete, nullptr);
    const ElasticCondensation& cond = concrete->condensation();
    Index held_before_damage = 0, held_intact = 0;
    for (int k = 1; k <= kSteps / 2; ++k) {
      sim.step();
      if (sim.damaged_points() == 0 && sim.broken_points() == 0)
        held_before_damage = std::max(held_before_damage, sim.held_contacts());
      for (std::size_t c = 0; c < cond.held.held.size(); ++c)
        held_intact += cond.held.held[c] && cond.intact[c];
    }
    if (on) {
      EXPECT_GE(held_before_damage, 1) << "an intact contact held before any point is damaged";
      EXPECT_GT(held_intact, 10000) << "contact-steps held intact";
    } else {
      EXPECT_EQ(held_before_damage, 0);
      EXPECT_EQ(held_intact, 0);
    }
    std::printf(
        "hold_intact_contacts = %d: most held before any damage %lld, intact held "
        "contact-steps %lld\n",
        on, static_cast<long long>(held_before_damage), static_cast<long long>(held_intact));
  }
}

// The bound is sound: no point of a contact kept held leaves the linear range. A read brings the
// held contacts' points up to the last step through the law itself (one update from their entry
// histories), so a point that crossed a limit while held would come back from the read with more
// damage than it entered with (D never decreases, S4); none does, none stands above its cap, and
// every broken point of a held contact comes back open, carrying nothing. A softening point of a
// held contact comes back on its normal envelope (fn = (1 - D) fn_max) with its damage grown but
// not broken, and its shear below its shrunken cap (held contacts with broken points and with
// softening points are met).
TEST(HeldContacts, NoHeldPointLeavesItsRoom) {
  const Scenario sc = pulled_box(true);
  Simulation sim(sc, build_specimen(sc));
  const ConcreteContacts* concrete = concrete_part(sim);
  ASSERT_NE(concrete, nullptr);
  const ContactNetwork& net = sim.specimen().contacts;
  Index checked = 0, with_broken = 0, softening_points = 0;
  for (int k = 1; k <= kSteps; ++k) {
    sim.step();
    if (k % 5 != 0) continue;
    // Before the read: the held contacts' points as they entered (or as an earlier read left them).
    const std::vector<std::uint8_t> held = concrete->condensation().held.held;
    std::vector<Real> before(static_cast<std::size_t>(net.point_count()), 0.0);
    const auto& stored = concrete->state().point.records;
    for (std::size_t m = 0; m < before.size(); ++m) before[m] = stored[m].history.damage;
    const auto& read = sim.contacts().point.records;  // caught up
    for (Index c = 0; c < net.contact_count(); ++c) {
      if (!held[static_cast<std::size_t>(c)]) continue;
      const bool softening = concrete->condensation().held.sums(c).slope_n < 0;
      for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
        const auto i = static_cast<std::size_t>(m);
        const PlanePointState& h = read[i].history;
        const LocalPointConstants& kc = read[i].constants;
        if (softening && before[i] < 1) {
          ASSERT_GE(h.damage, before[i]) << "step " << k << ", contact " << c << ", point " << m;
          ASSERT_LT(h.damage, 1.0) << "step " << k << ", contact " << c << ", point " << m;
          ASSERT_EQ(h.fn, (1 - h.damage) * kc.fn_max) << "step " << k << ", contact " << c;
          ASSERT_LT(std::sqrt(h.fs.squaredNorm()), (1 - h.damage) * kc.c_max) << "step " << k;
          ++softening_points;
          continue;
        }
        ASSERT_EQ(h.damage, before[i]) << "step " << k << ", contact " << c << ", point " << m;
        ASSERT_LE(h.fn, (1 - h.damage) * kc.fn_max) << "step " << k;
        if (h.damage < 1) continue;
        ASSERT_EQ(h.fn, 0.0) << "step " << k << ", contact " << c << ", point " << m;
        ASSERT_EQ(h.fs.squaredNorm(), 0.0) << "step " << k << ", contact " << c;
      }
      ++checked;
      with_broken += concrete->condensation().held.sums(c).open_margin >= 0;
    }
  }
  EXPECT_GT(checked, 10000) << "the test must meet held contacts";
  EXPECT_GT(with_broken, 1000) << "... and held contacts with broken points";
  EXPECT_GT(softening_points, 1000) << "... and softening points of held contacts";
  std::printf("held contacts checked %lld, with broken points %lld; softening points %lld\n",
              static_cast<long long>(checked), static_cast<long long>(with_broken),
              static_cast<long long>(softening_points));
}

// A broken point of a held contact carries nothing only while its opening grows (its force is
// kn min(0, un - M), M its largest opening), and a softening point follows its envelope only while
// its opening grows, so a contact with broken or softening points stays held only while each step
// opens them further (the kernel's per-step test): read at every step (reads change nothing,
// above), every such point of a contact held after a step is at least as open as it was after the
// step before.
TEST(HeldContacts, BrokenAndSofteningPointsOfAHeldContactKeepOpening) {
  const Scenario sc = pulled_box(true);
  Simulation sim(sc, build_specimen(sc));
  const ConcreteContacts* concrete = concrete_part(sim);
  ASSERT_NE(concrete, nullptr);
  const ContactNetwork& net = sim.specimen().contacts;
  std::vector<Real> last_un(static_cast<std::size_t>(net.point_count()), 0.0);
  Index broken = 0, softening = 0;
  for (int k = 1; k <= kSteps; ++k) {
    sim.step();
    const HeldContacts& h = concrete->condensation().held;
    const auto& points = sim.contacts().point.records;  // caught up
    for (Index c = 0; c < net.contact_count(); ++c) {
      if (k == 1 || !h.held[static_cast<std::size_t>(c)]) continue;
      const bool softening_contact = h.sums(c).slope_n < 0;
      for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
        const auto i = static_cast<std::size_t>(m);
        const Real d = points[i].history.damage;
        if (d < 1 && !softening_contact) continue;
        ASSERT_GE(points[i].history.un, last_un[i]) << "step " << k << ", contact " << c;
        ++(d < 1 ? softening : broken);
      }
    }
    for (std::size_t i = 0; i < last_un.size(); ++i) last_un[i] = points[i].history.un;
  }
  EXPECT_GT(broken, 10000) << "the test must meet broken points of held contacts";
  EXPECT_GT(softening, 1000) << "... and softening points of held contacts";
}

// A held contact's force, moments and the energy its softening points dissipate, from its sums,
// are its points' to rounding: read at every step (reads change nothing, above), each contact held
// through the step (by the same entry) has the force of its points caught up, sum phi_J with
// phi_J = -fn n + fs in its stored frame, their moment sum rho_J x phi_J about A's centre at the
// poses of the evaluation (rho_J = u0 / 2 + (R_A + R_B) / 2 (p_J0 - x_A0), u0 = dx - R_B r0:
// contact_loop.hpp), and dissipates what the law's trapezoid gives each point from the step before,
// (fn_old + fn) / 2 (fn_old + kn (un - un_old) - fn) / kn (SPEC 11). Held contacts with inside
// points and with softening points are met.
TEST(HeldContacts, AHeldContactsForceMomentsAndDissipationAreItsPoints) {
  const Scenario sc = pulled_box(true);
  Simulation sim(sc, build_specimen(sc));
  const ConcreteContacts* concrete = concrete_part(sim);
  ASSERT_NE(concrete, nullptr);
  const ContactNetwork& net = sim.specimen().contacts;
  const auto points_n = static_cast<std::size_t>(net.point_count());
  std::vector<Real> last_un(points_n, 0.0), last_fn(points_n, 0.0);
  constexpr Real kNone = std::numeric_limits<Real>::quiet_NaN();
  std::vector<std::array<Real, 3>> entry(static_cast<std::size_t>(net.contact_count()),
                                         {kNone, kNone, kNone});
  Index checked = 0, dissipating = 0;
  for (int k = 1; k <= kSteps; ++k) {
    // The poses the step evaluates the contacts at.
    const std::vector<Vec3> x = sim.bodies().position;
    const std::vector<Quat> q = sim.bodies().orientation;
    sim.step();
    const HeldContacts& h = concrete->condensation().held;
    const ContactState& cs = sim.contacts();  // caught up
    const auto& points = cs.point.records;
    const std::vector<Vec3>& x0 = sim.bodies().position0;
    for (Index c = 0; c < net.contact_count(); ++c) {
      std::array<Real, 3>& e = entry[static_cast<std::size_t>(c)];
      const std::array<Real, 3> last = e;
      e = {kNone, kNone, kNone};
      if (!h.held[static_cast<std::size_t>(c)]) continue;
      e = {h.sums(c).disp0[0], h.sums(c).disp0[1], h.sums(c).disp0[2]};
      if (e != last) continue;  // not held through the step
      const Vec3 n = cs.normal[c], t1 = cs.tangent[c], t2 = n.cross(t1);
      const auto a = static_cast<std::size_t>(net.particle_a[c]),
                 b = static_cast<std::size_t>(net.particle_b[c]);
      const Eigen::Matrix3d ra = q[a].toRotationMatrix(), rb = q[b].toRotationMatrix();
      const Vec3 dx = x[b] - x[a], u0 = dx - rb * (x0[b] - x0[a]);
      Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
      Real scale = 0, m_scale = 0, dissipated = 0, d_scale = 0;
      for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
        const auto i = static_cast<std::size_t>(m);
        const PlanePointState& p = points[i].history;
        const Real kn = points[i].constants.kn;
        const Vec3 phi = -p.fn * n + p.fs.x * t1 + p.fs.y * t2;
        const Vec3 r = Vec3(points[i].x0, points[i].y0, points[i].z0) - x0[a];
        const Vec3 rho = 0.5 * u0 + 0.5 * (ra + rb) * r;
        force += phi;
        moment += rho.cross(phi);
        scale += phi.norm();
        m_scale += rho.norm() * phi.norm();
        const Real mean = 0.5 * (last_fn[i] + p.fn);
        const Real change = (last_fn[i] + kn * (p.un - last_un[i]) - p.fn) / kn;
        dissipated += mean * change;
        // What rounding in the difference of its terms can leave.
        d_scale += std::abs(mean) * (std::abs(p.un) + std::abs(last_un[i]) +
                                     (std::abs(last_fn[i]) + std::abs(p.fn)) / kn);
      }
      ASSERT_LE((force - cs.force_b[c]).norm(), 1e-9 * scale) << "step " << k << ", contact " << c;
      ASSERT_LE((-moment - cs.torque_a[c]).norm(), 1e-9 * m_scale) << "step " << k << ", " << c;
      ASSERT_LE((moment - dx.cross(force) - cs.torque_b[c]).norm(),
                1e-9 * (m_scale + dx.norm() * scale))
          << "step " << k << ", contact " << c;
      ASSERT_NEAR(cs.dissipated_damage[c], dissipated, 1e-9 * d_scale + 1e-30)
          << "step " << k << ", contact " << c;
      ++checked;
      dissipating += cs.dissipated_damage[c] > 0;
    }
    for (std::size_t i = 0; i < points_n; ++i) {
      last_un[i] = points[i].history.un;
      last_fn[i] = points[i].history.fn;
    }
  }
  EXPECT_GT(checked, 100000) << "the test must meet held contacts";
  EXPECT_GT(dissipating, 1000) << "... and held contacts whose softening points dissipate";
  std::printf("held contacts checked %lld, dissipating %lld\n", static_cast<long long>(checked),
              static_cast<long long>(dissipating));
}

// With holding, the energy a history row reads is kept by the step (evaluate_held), and it is the
// same bits as the pass after the step (ConcreteContacts::held_energy).
TEST(HeldContacts, StrainEnergyKeptByTheStepEqualsTheSumAfterIt) {
  const Scenario sc = pulled_box(true);
  Simulation kept(sc, build_specimen(sc)), summed(sc, build_specimen(sc));
  kept.keep_strain_energy_every(3);
  Index with_held = 0;
  for (int k = 1; k <= kSteps; ++k) {
    kept.step();
    summed.step();
    if (k % 3 != 0) continue;
    ASSERT_EQ(kept.strain_energy(), summed.strain_energy()) << "step " << k;
    with_held += kept.held_contacts() > 0;
  }
  EXPECT_GT(with_held, 100);
}

// The same bits at 1 and 2 threads, and for a run restored from a checkpoint (which keeps the held
// contacts, their sums and entry histories) against the run that wrote it.
TEST(HeldContacts, SameBitsForAnyThreadCountAndAfterARestart) {
  const Scenario sc = pulled_box(true);
  set_threads(1);
  Simulation one(sc, build_specimen(sc));
  for (int k = 0; k < kSteps; ++k) one.step();
  set_threads(2);
  Simulation two(sc, build_specimen(sc));
  for (int k = 0; k < kSteps; ++k) two.step();
  EXPECT_EQ(load(one), load(two));
  EXPECT_EQ(one.strain_energy(), two.strain_energy());

  const fs::path dir =
      fs::temp_directory_path() / ("rcdem_held_restart_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Simulation writer(sc, build_specimen(sc)), restored(sc, build_specimen(sc));
  for (int k = 0; k < kSteps / 2; ++k) writer.step();
  ASSERT_GT(writer.held_contacts(), 0);
  const fs::path file =
      io::write_checkpoint(dir, io::CheckpointParts{&writer, nullptr, nullptr, nullptr}, 0);
  io::restore_checkpoint(file, io::CheckpointParts{&restored, nullptr, nullptr, nullptr}, 0);
  EXPECT_EQ(restored.held_contacts(), writer.held_contacts());
  for (int k = 0; k < kSteps / 2; ++k) {
    writer.step();
    restored.step();
    ASSERT_EQ(load(writer), load(restored)) << "step " << k;
  }
  EXPECT_EQ(load(writer), load(restored));
  EXPECT_EQ(writer.strain_energy(), restored.strain_energy());
  EXPECT_EQ(writer.damaged_points(), restored.damaged_points());
  fs::remove_all(dir);
}

// The softening clock (held_contacts.hpp): in the pulled box some softening holds end within
// kShortSofteningHold steps and their contacts wait; a waiting contact is never held as softening;
// and a checkpoint keeps every clock, so that a run restored where contacts wait continues with
// the writer's bits (the restart above, at a step chosen for waiting clocks).
TEST(HeldContacts, ShortSofteningHoldsWaitAndACheckpointKeepsTheirClocks) {
  const Scenario sc = pulled_box(true);
  Simulation writer(sc, build_specimen(sc)), restored(sc, build_specimen(sc));
  const ConcreteContacts* concrete = concrete_part(writer);
  ASSERT_NE(concrete, nullptr);
  const HeldContacts& h = concrete->condensation().held;
  Index waiting_steps = 0, step = 0;
  for (; step < kSteps; ++step) {
    writer.step();
    Index waiting = 0;
    for (std::size_t c = 0; c < h.held.size(); ++c) {
      const std::int16_t clock = h.softening_clock[c];
      ASSERT_GE(clock, -kSofteningBackoff);
      ASSERT_LE(clock, kShortSofteningHold);
      if (clock < 0) ++waiting;
      // A contact held as softening counts its steps; one that waits is not held as softening.
      if (h.held[c] && h.sums(static_cast<Index>(c)).slope_n < 0) ASSERT_GE(clock, 0) << c;
    }
    if (waiting > 0) ++waiting_steps;
    if (waiting > 20 && step > kSteps / 2) break;
  }
  ASSERT_LT(step, kSteps) << "no step with more than 20 contacts waiting";
  EXPECT_GT(waiting_steps, 100);
  const fs::path dir =
      fs::temp_directory_path() / ("rcdem_held_clock_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file =
      io::write_checkpoint(dir, io::CheckpointParts{&writer, nullptr, nullptr, nullptr}, 0);
  io::restore_checkpoint(file, io::CheckpointParts{&restored, nullptr, nullptr, nullptr}, 0);
  EXPECT_EQ(concrete_part(restored)->condensation().held.softening_clock, h.softening_clock);
  for (int k = 0; k < 1000; ++k) {
    writer.step();
    restored.step();
    ASSERT_EQ(load(writer), load(restored)) << "step " << k;
  }
  EXPECT_EQ(writer.strain_energy(), restored.strain_energy());
  fs::remove_all(dir);
}

// The held contacts' kernel gives a contact the same bits wherever it stands in the block's list
// and however long the list is (a lane computes alone; a list is run to whole vectors, its last
// contact repeated): what makes a run's bits independent of the thread count. Every sub-list of a
// cracked block's held contacts against the whole list, output by output.
TEST(HeldContacts, TheKernelGivesAContactTheSameBitsWhereverItIsListed) {
  const Scenario sc = pulled_box(true);
  Simulation sim(sc, build_specimen(sc));
  for (int k = 0; k < 2500; ++k) sim.step();  // past the peak (about step 1,500)
  const ConcreteContacts* concrete = concrete_part(sim);
  ASSERT_NE(concrete, nullptr);
  const ContactNetwork& net = sim.specimen().contacts;
  const ElasticCondensation& cond = concrete->condensation();
  const HeldContacts& h = cond.held;
  // The block with the most held contacts.
  Index best = -1, most = 0;
  for (Index begin = 0; begin < net.contact_count(); begin += HeldContacts::kBlock) {
    Index n = 0;
    for (Index c = begin; c < std::min(begin + HeldContacts::kBlock, net.contact_count()); ++c)
      n += h.held[static_cast<std::size_t>(c)];
    if (n > most) most = n, best = begin;
  }
  ASSERT_GE(most, 17) << "the test needs a block with more than two vectors of held contacts";
  std::vector<Index> list;
  for (Index c = best; c < std::min(best + HeldContacts::kBlock, net.contact_count()); ++c)
    if (h.held[static_cast<std::size_t>(c)]) list.push_back(c);
  const Bodies& bodies = sim.bodies();
  const BodyPoses poses = BodyPoses::of(bodies.position, bodies.orientation);
  const ContactState& cs = concrete->state();
  const HeldInputs in{cond.sums,
                      net.particle_a.data(),
                      net.particle_b.data(),
                      poses.ptr(),
                      bodies.angular_velocity.data()->data(),
                      cs.normal.data()->data(),
                      cs.tangent.data()->data(),
                      sim.time_step(),
                      reinterpret_cast<const Real*>(&h.sums(best)),
                      best};
  const auto whole = std::make_unique<HeldOutputs>();
  evaluate_held_block(in, list.data(), static_cast<Index>(list.size()), true, *whole);
  // Each output of entry k as doubles (kept as a number too).
  const auto outputs = [](const HeldOutputs& o, Index k) {
    std::vector<Real> v;
    for (int i = 0; i < 3; ++i)
      for (const auto* a : {o.force, o.torque_b, o.torque_a, o.n, o.t1, o.dd_n}) v.push_back(a[i][k]);
    for (const Real x : {o.energy[k], o.du_n[k], o.dissipated[k], Real(o.kept[k])}) v.push_back(x);
    return v;
  };
  const auto part = std::make_unique<HeldOutputs>();
  Index compared = 0;
  for (std::size_t first = 0; first < list.size(); first += 3)
    for (std::size_t count = 1; first + count <= list.size(); ++count) {
      evaluate_held_block(in, list.data() + first, static_cast<Index>(count), true, *part);
      for (std::size_t k = 0; k < count; ++k) {
        const std::vector<Real> a = outputs(*whole, static_cast<Index>(first + k));
        const std::vector<Real> b = outputs(*part, static_cast<Index>(k));
        ASSERT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)))
            << "contact " << list[first + k] << " at " << k << " of " << count;
        ++compared;
      }
    }
  EXPECT_GT(compared, 1000);
}
