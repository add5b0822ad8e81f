// The exponential-softening damage law (contact/laws/exponential_softening.hpp) at one local point
// against its analytic curve, and in a specimen through the solver. The point is the realistic one
// of test_contact_laws.cpp: A_c = 2e-5 m^2, d = 8.5e-3 m, paper Table 2 properties. Energies are
// booked here independently of the law (trapezoidal work of the point's forces).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/laws/exponential_softening.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

using namespace rcdem;

namespace {

constexpr Real kArea = 2e-5;
constexpr Real kDistance = 8.5e-3;

ExponentialSoftening table2() {
  const ContactParameters p;  // paper Table 2
  return std::get<ExponentialSoftening>(make_contact_law("exponential", p));
}

LocalPointConstants point_constants(const ExponentialSoftening& law, Real distance = kDistance) {
  const ContactParameters p;
  LocalPointConstants c;
  c.kn = p.E_bar * kArea / distance;  // (3)
  c.ks = p.alpha * c.kn;              // (4)
  c.fn_max = law.sigma_nt * kArea;    // (5)
  c.c_max = p.tau * kArea;            // (6)
  return c;
}

// One point driven by displacements, with its own ledger: work by the trapezoid, the stored
// energy by the law's formula, the dissipation by the law.
struct Driver {
  const ExponentialSoftening& law;
  LocalPointConstants c;
  LocalPointState s;
  Real work = 0, dissipated = 0;

  void to(Real u_n, const Vec3& u_s = Vec3::Zero()) {
    const Real fn0 = s.fn, un0 = s.un, d0 = s.damage;
    const Vec3 fs0 = s.fs, us0 = s.us;
    const LawResult r = law.update(c, s, u_n, u_s);
    EXPECT_GE(s.damage, d0);
    EXPECT_EQ(r.damage_grew, s.damage > d0);
    EXPECT_GE(r.dissipated, 0.0);
    work += 0.5 * (fn0 + s.fn) * (u_n - un0) - 0.5 * (fs0 + s.fs).dot(u_s - us0);
    dissipated += r.dissipated;
  }
  Real stored() const { return law.elastic_energy(c, s); }
};

}  // namespace

// Monotone opening: elastic to u_0, then F_n,max exp(-(u - u_0)/u_f); the energy dissipated to
// full separation is G_f,n A_c, booked by the law (exact integral) and by the point's work.
TEST(ExponentialSoftening, MonotonicTensionFollowsTheCurveAndDissipatesGfn) {
  const ExponentialSoftening law = table2();
  Driver p{law, point_constants(law)};
  const Real u_0 = p.c.fn_max / p.c.kn, u_f = law.decay_length(u_0);
  ASSERT_GT(u_f, u_0);                // a softening point, not a brittle one
  const Real u_end = u_0 + 40 * u_f;  // exp(-40): the rest of the curve holds 4e-18 of G_f A
  const int steps = 20000;
  Real worst = 0, peak = 0;
  for (int i = 1; i <= steps; ++i) {
    const Real u = u_end * i / steps;
    p.to(u);
    const Real expected = u <= u_0 ? p.c.kn * u : p.c.fn_max * std::exp(-(u - u_0) / u_f);
    worst = std::max(worst, std::abs(p.s.fn - expected));
    peak = std::max(peak, p.s.fn);
  }
  const Real GA = law.G_fn * kArea;
  EXPECT_LT(worst, 1e-12 * p.c.fn_max);
  // Never above F_n,max; below it by at most the slope times the step that samples the peak.
  EXPECT_LE(peak, p.c.fn_max);
  EXPECT_GT(peak, p.c.fn_max - p.c.kn * u_end / steps);
  // The law's sum telescopes to the closed form at u_end, up to the rounding of each step's
  // difference of two values of about G_f A (a few ulps each).
  EXPECT_NEAR(p.dissipated / GA, 1.0, 5e-15 * steps);
  // The trapezoid's error over a step of u_end / 20000 on a curve of length u_f.
  EXPECT_NEAR(p.work / GA, 1.0, 1e-4);
  EXPECT_LT(p.stored(), 1e-15 * GA);
  EXPECT_NEAR(p.s.damage, 1.0, 1e-15);
}

// Regularised by the fracture energy: a point twice as long or half as long (other kn, so other
// u_0 and u_f) dissipates the same G_f,n A_c; the peak force is F_n,max for each.
TEST(ExponentialSoftening, DissipatedEnergyDoesNotDependOnThePointsStiffness) {
  const ExponentialSoftening law = table2();
  for (const Real d : {0.5 * kDistance, kDistance, 2.0 * kDistance}) {
    Driver p{law, point_constants(law, d)};
    const Real u_0 = p.c.fn_max / p.c.kn;
    const Real u_end = u_0 + 40 * law.decay_length(u_0);
    for (int i = 1; i <= 4000; ++i) p.to(u_end * i / 4000);
    EXPECT_NEAR(p.dissipated / (law.G_fn * kArea), 1.0, 5e-15 * 4000) << "d = " << d;
    EXPECT_NEAR(p.work / (law.G_fn * kArea), 1.0, 2e-3) << "d = " << d;
  }
}

// Unloading under damage goes back to the origin along the secant (1 - D) kn, dissipating nothing;
// reloading retraces it and meets the softening curve where it left it; closing the crack gives
// the full stiffness in compression.
TEST(ExponentialSoftening, UnloadsToTheOriginUnderDamage) {
  const ExponentialSoftening law = table2();
  Driver p{law, point_constants(law)};
  const Real u_0 = p.c.fn_max / p.c.kn, u_f = law.decay_length(u_0);
  const Real kappa = u_0 + u_f;  // past the peak: D = 1 - exp(-1) u_0 / kappa
  for (int i = 1; i <= 1000; ++i) p.to(kappa * i / 1000);
  const Real d = p.s.damage;
  EXPECT_NEAR(d, 1 - (u_0 / kappa) * std::exp(-1.0), 1e-15);
  const Real secant = (1 - d) * p.c.kn;
  const Real dissipated = p.dissipated;
  for (int i = 999; i >= 0; --i) {
    const Real u = kappa * i / 1000;
    p.to(u);
    EXPECT_NEAR(p.s.fn, secant * u, 1e-12 * p.c.fn_max);
  }
  EXPECT_EQ(p.s.fn, 0.0);  // at the origin, exactly
  EXPECT_EQ(p.s.damage, d);
  EXPECT_EQ(p.dissipated, dissipated);
  EXPECT_NEAR(p.stored(), 0.0, 1e-30);
  // The unloading and reloading are elastic on the secant: the work returns what it stored.
  const Real work_at_origin = p.work;
  p.to(-0.5 * u_0);
  EXPECT_EQ(p.s.fn, -0.5 * u_0 * p.c.kn);  // a closed crack: the full stiffness
  p.to(0.0);
  for (int i = 1; i <= 1000; ++i) p.to(kappa * i / 1000);
  EXPECT_EQ(p.s.damage, d);
  EXPECT_NEAR(p.s.fn, p.c.fn_max * std::exp(-(kappa - u_0) / u_f), 1e-12 * p.c.fn_max);
  EXPECT_NEAR(p.work - work_at_origin, p.stored(), 1e-9 * p.stored());
  p.to(1.01 * kappa);  // and goes on softening past kappa
  EXPECT_GT(p.s.damage, d);
}

// Shear: the cohesion is (1 - D) c_max, and compression adds Coulomb friction mu_c |fn| (S5).
TEST(ExponentialSoftening, ShearCapIsTheDamagedCohesionPlusFriction) {
  const ExponentialSoftening law = table2();
  Driver p{law, point_constants(law)};
  const Real u_0 = p.c.fn_max / p.c.kn, u_f = law.decay_length(u_0);
  for (int i = 1; i <= 100; ++i) p.to((u_0 + 2 * u_f) * i / 100);
  const Real d = p.s.damage;
  ASSERT_GT(d, 0.5);
  // Close the crack to a compression, then slip far past the elastic range.
  const Real u_n = -0.2 * u_0;
  p.to(0.0);
  p.to(u_n);
  const Vec3 t(0.6, 0.8, 0.0);
  const Real slip = 50 * p.c.c_max / p.c.ks;
  const Real work0 = p.work, stored0 = p.stored(), dissipated0 = p.dissipated;
  for (int i = 1; i <= 500; ++i) p.to(u_n, Vec3(slip * i / 500 * t));
  const Real cap = (1 - d) * p.c.c_max + law.mu_c * p.c.kn * 0.2 * u_0;
  EXPECT_NEAR(p.s.fs.norm(), cap, 1e-12 * cap);
  EXPECT_NEAR(p.s.fs.normalized().dot(-t), 1.0, 1e-12);  // resists the slip
  EXPECT_EQ(p.s.damage, d);                              // slip alone does not damage
  // What the slip dissipated is the work it did not store, but for the one step that rises to the
  // cap, booked at the capped force (shear_envelope.hpp): a step's slip 0.1 c_max / ks of ~45.
  const Real slip_dissipated = p.dissipated - dissipated0;
  EXPECT_NEAR((p.work - work0) - (p.stored() - stored0), slip_dissipated, 1e-3 * slip_dissipated);
}

// A point whose fracture energy is below its elastic energy at the peak cannot soften: it breaks at
// u_0, dissipating what it stored, and never yields a NaN.
TEST(ExponentialSoftening, BrittlePointBreaksAtItsStrength) {
  ExponentialSoftening law = table2();
  Driver probe{law, point_constants(law)};
  const Real u_0 = probe.c.fn_max / probe.c.kn;
  law.G_fn = 0.25 * law.sigma_nt * u_0;  // G_f / sigma < u_0 / 2
  Driver p{law, probe.c};
  ASSERT_LE(law.decay_length(u_0), 0.0);
  for (int i = 1; i <= 100; ++i) p.to(2 * u_0 * i / 100);
  EXPECT_EQ(p.s.damage, 1.0);
  EXPECT_EQ(p.s.fn, 0.0);
  EXPECT_TRUE(std::isfinite(p.dissipated));
  EXPECT_NEAR(p.work - p.stored(), p.dissipated, 0.03 * p.dissipated);  // one step's kink
}

// Through the solver: a small box pulled apart between glued platens with contact.law =
// "exponential" cracks through, and the energy ledger balances (SPEC 11).
TEST(ExponentialSoftening, BoxInTensionCracksAndTheLedgerBalances) {
  const Scenario sc = parse_scenario(R"(
[specimen]
shape = "box"
size = [0.04, 0.04, 0.04]
[generation]
seed = 2
relaxation_iterations = 100
[contact]
law = "exponential"
[solver]
damping = 0.7
[plates.bottom]
face = "z-"
glued = true
[plates.top]
face = "z+"
glued = true
velocity = 0.005
ramp_time = 4.0e-5
[loading]
control_plate = "top"
)",
                                     "exponential_box.toml");
  Simulation sim(sc, build_specimen(sc));
  Real peak = 0, load = 0;
  int steps = 0;
  for (; steps < 40000; ++steps) {
    sim.step();
    load = -sim.find_plate("top")->force.z();
    peak = std::max(peak, load);
    if (peak > 0 && load < 0.2 * peak) break;
  }
  const Energy e = sim.energy();
  EXPECT_LT(steps, 40000) << "no crack through: load " << load << " N of a peak " << peak << " N";
  EXPECT_GT(sim.damaged_points() + sim.broken_points(), 0);
  EXPECT_GT(e.damage, 0.0);
  EXPECT_LT(e.balance_error(), 1e-3);
  std::printf("[exponential box] peak %.4g N, %d steps, damage %.4g J, balance error %.3g\n", peak,
              steps, e.damage, e.balance_error());
}
