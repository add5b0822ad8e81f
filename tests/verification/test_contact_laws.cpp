// Contact laws at one local point against their analytic curves (SPEC 5). The point is a
// realistic one: A_c = 2e-5 m^2, d = 8.5e-3 m, paper Table 2 properties, so kn = E_bar A_c / d (3)
// and ks = alpha kn (4). Energies are booked here independently of the law (trapezoidal work of
// the point's forces), so the law's own LawResult.dissipated is checked, not trusted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <type_traits>

#include "rcdem/contact/laws/bilinear_softening.hpp"
#include "rcdem/contact/laws/elastic.hpp"
#include "rcdem/contact/laws/local_point_state.hpp"

using namespace rcdem;

namespace {

constexpr Real kArea = 2e-5;
constexpr Real kDistance = 8.5e-3;
constexpr Real kEbar = 48.7e9;
constexpr Real kAlpha = 0.3;

BilinearSoftening table2() {
  BilinearSoftening law;
  law.sigma_nt = 4.15e6;
  law.tau = 21.0e6;
  law.G_fn = 9.002;
  law.G_fs = 2380.785;
  law.mu_c = 0.5;
  return law;
}

LocalPointConstants point_constants(const BilinearSoftening& law) {
  LocalPointConstants c;
  c.kn = kEbar * kArea / kDistance;  // (3)
  c.ks = kAlpha * c.kn;              // (4)
  c.fn_max = law.sigma_nt * kArea;   // (5)
  c.c_max = law.tau * kArea;         // (6)
  return c;
}

// One point driven by displacement increments, with its own energy ledger.
struct Driver {
  LocalPointConstants c;
  LocalPointState s;
  Real work = 0;
  Real dissipated = 0;
  Real friction = 0;
  bool damage_grew = false;
  Real worst_step_balance = 0;  // max |work - dE - dissipated| over steps

  // Energy not accounted for since the start (trapezoidal work against stored + dissipated).
  Real ledger_gap() const { return work - elastic_energy() - dissipated; }

  Real elastic_energy() const { return s.fn * s.fn / (2 * c.kn) + s.fs.squaredNorm() / (2 * c.ks); }

  template <typename Law>
  LawResult step(const Law& law, Real dun, const Vec3& dus) {
    const Real fn0 = s.fn;
    const Vec3 fs0 = s.fs;
    const Real e0 = elastic_energy();
    const Real d0 = s.damage;
    const LawResult r = law.update(c, s, s.un + dun, Vec3(s.us + dus));  // totals
    EXPECT_GE(s.damage, d0);
    EXPECT_EQ(r.damage_grew, s.damage > d0);
    EXPECT_GE(r.dissipated, 0.0);
    EXPECT_GE(r.dissipated_friction, 0.0);
    EXPECT_LE(r.dissipated_friction, r.dissipated);
    const Real w = 0.5 * (fn0 + s.fn) * dun - 0.5 * (fs0 + s.fs).dot(dus);
    work += w;
    dissipated += r.dissipated;
    friction += r.dissipated_friction;
    damage_grew = damage_grew || r.damage_grew;
    worst_step_balance =
        std::max(worst_step_balance, std::abs(w - (elastic_energy() - e0) - r.dissipated));
    return r;
  }
};

// Monotonic tension triangle: elastic to u_n0, linear softening to zero at u_nu (S2)-(S5).
Real tension_triangle(const LocalPointConstants& c, Real u_nu, Real un) {
  const Real u_n0 = c.fn_max / c.kn;
  if (un <= u_n0) return c.kn * un;
  return std::max<Real>(0, c.fn_max * (u_nu - un) / (u_nu - u_n0));
}

}  // namespace

TEST(BilinearSoftening, Table2PointIsSofteningNotBrittle) {
  const BilinearSoftening law = table2();
  const LocalPointConstants c = point_constants(law);
  // The tests below rely on both softening branches existing.
  EXPECT_GT(law.u_nu(), 2 * c.fn_max / c.kn);
  EXPECT_GT(law.u_su(), 2 * c.c_max / c.ks);
  EXPECT_NEAR(law.u_nu(), 2 * 9.002 / 4.15e6, 1e-18);  // (S2)
}

TEST(BilinearSoftening, MonotonicTensionFollowsTriangleAndDissipatesGfn) {
  const BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  const Real u_nu = law.u_nu();
  const Real u_n0 = p.c.fn_max / p.c.kn;
  const int steps = 2000;
  const Real du = 1.2 * u_nu / steps;
  Real peak = 0, un_at_peak = 0, worst = 0;
  for (int i = 0; i < steps; ++i) {
    p.step(law, du, Vec3::Zero());
    if (p.s.fn > peak) peak = p.s.fn, un_at_peak = p.s.un;
    worst = std::max(worst, std::abs(p.s.fn - tension_triangle(p.c, u_nu, p.s.un)));
  }
  const Real GA = law.G_fn * kArea;
  EXPECT_NEAR(peak / (law.sigma_nt * kArea), 1.0, 0.01);
  EXPECT_NEAR(un_at_peak, u_n0, du);
  EXPECT_LT(worst, 0.01 * p.c.fn_max);
  EXPECT_NEAR(p.work / GA, 1.0, 0.01);
  EXPECT_NEAR(p.dissipated / GA, 1.0, 0.01);
  // The law integrates the kink at the peak slightly differently from the trapezoid: O(du).
  EXPECT_LT(std::abs(p.ledger_gap()), 1e-3 * GA);
  EXPECT_EQ(p.friction, 0.0);
  EXPECT_EQ(p.s.damage, 1.0);
  EXPECT_TRUE(p.s.fs.isZero());

  // Fully damaged: opening further carries no tension at all.
  for (int i = 0; i < 100; ++i) {
    p.step(law, 0.01 * u_nu, Vec3::Zero());
    EXPECT_LE(p.s.fn, 1e-12 * p.c.fn_max);
  }
  EXPECT_NEAR(p.work / GA, 1.0, 0.01);
}

TEST(BilinearSoftening, MonotonicShearWithoutNormalForceDissipatesGfs) {
  const BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  const Real u_su = law.u_su();
  const Real u_s0 = p.c.c_max / p.c.ks;
  const Vec3 dir(0.6, 0.8, 0.0);
  const int steps = 2000;
  const Real du = 1.2 * u_su / steps;
  Real peak = 0, worst = 0;
  for (int i = 0; i < steps; ++i) {
    p.step(law, 0.0, du * dir);
    const Real us = p.s.us.norm();
    const Real expected =
        us <= u_s0 ? p.c.ks * us : std::max<Real>(0, p.c.c_max * (u_su - us) / (u_su - u_s0));
    worst = std::max(worst, std::abs(p.s.fs.norm() - expected));
    peak = std::max(peak, p.s.fs.norm());
    // The shear force opposes the slip (force on B is -fn n + fs).
    EXPECT_LE(p.s.fs.dot(dir), 0.0);
    EXPECT_EQ(p.s.fn, 0.0);
  }
  const Real GA = law.G_fs * kArea;
  EXPECT_NEAR(peak / (law.tau * kArea), 1.0, 0.01);
  EXPECT_LT(worst, 0.01 * p.c.c_max);
  EXPECT_NEAR(p.work / GA, 1.0, 0.01);
  EXPECT_NEAR(p.dissipated / GA, 1.0, 0.01);
  EXPECT_LT(std::abs(p.ledger_gap()), 1e-3 * GA);
  EXPECT_EQ(p.friction, 0.0);
  EXPECT_EQ(p.s.damage, 1.0);
  EXPECT_LT(p.s.fs.norm(), 1e-12 * p.c.c_max);
}

TEST(BilinearSoftening, ShearUnderCompressionLeavesCoulombFriction) {
  const BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  const Real P = 2.0 * p.c.fn_max;  // compression, well inside the unlimited elastic range
  for (int i = 0; i < 10; ++i) p.step(law, -0.1 * P / p.c.kn, Vec3::Zero());
  EXPECT_NEAR(p.s.fn / -P, 1.0, 1e-12);
  EXPECT_EQ(p.dissipated, 0.0);
  EXPECT_EQ(p.s.damage, 0.0);

  const Vec3 dir(0.0, -1.0, 0.0);
  const int steps = 2000;
  const Real du = 1.2 * law.u_su() / steps;
  Real peak = 0;
  for (int i = 0; i < steps; ++i) {
    p.step(law, 0.0, du * dir);
    peak = std::max(peak, p.s.fs.norm());
  }
  EXPECT_EQ(p.s.damage, 1.0);
  EXPECT_NEAR(p.s.fn / -P, 1.0, 1e-12);
  const Real friction = law.mu_c * P;
  EXPECT_NEAR(p.s.fs.norm() / friction, 1.0, 0.01);
  // Damage grows with |us| from u_s0 on (S3) while the force is still below the intact cap, so
  // the peak lies between C_max and C_max + mu_c P.
  EXPECT_GT(peak, p.c.c_max);
  EXPECT_LT(peak, p.c.c_max + friction);

  // Sliding at full damage: every joule goes to friction, mu_c P per metre of slip.
  const Real slip = 0.5 * law.u_su();
  const Real dissipated_before = p.dissipated;
  const Real friction_before = p.friction;
  for (int i = 0; i < 500; ++i) p.step(law, 0.0, (slip / 500) * dir);
  EXPECT_NEAR((p.dissipated - dissipated_before) / (friction * slip), 1.0, 0.01);
  EXPECT_NEAR((p.friction - friction_before) / (friction * slip), 1.0, 1e-9);
  EXPECT_NEAR(p.s.fs.norm() / friction, 1.0, 1e-12);
  EXPECT_LT(std::abs(p.ledger_gap()), 1e-3 * p.dissipated);
}

TEST(BilinearSoftening, UnloadsAndReloadsElasticallyFromTheSofteningBranch) {
  const BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  const Real u_nu = law.u_nu();
  const Real u_n0 = p.c.fn_max / p.c.kn;
  const Real du = u_nu / 2000;
  while (p.s.un < u_n0 + 0.5 * (u_nu - u_n0)) p.step(law, du, Vec3::Zero());
  const Real fn_p = p.s.fn;
  const Real d_p = p.s.damage;
  const Real un_p = p.s.un;
  ASSERT_GT(d_p, 0.4);
  ASSERT_LT(d_p, 0.6);
  EXPECT_NEAR(fn_p, (1 - d_p) * p.c.fn_max, 1e-12 * p.c.fn_max);

  // Unload into compression: slope kn, no damage, no dissipation.
  const Real dissipated_p = p.dissipated;
  const int back = 400;
  const Real dback = -2 * fn_p / p.c.kn / back;
  for (int i = 0; i < back; ++i) {
    const Real fn0 = p.s.fn;
    const LawResult r = p.step(law, dback, Vec3::Zero());
    EXPECT_NEAR((p.s.fn - fn0) / dback, p.c.kn, 1e-6 * p.c.kn);
    EXPECT_FALSE(r.damage_grew);
    EXPECT_EQ(r.dissipated, 0.0);
  }
  EXPECT_NEAR(p.s.fn, -fn_p, 1e-9 * p.c.fn_max);
  EXPECT_EQ(p.s.damage, d_p);
  EXPECT_EQ(p.dissipated, dissipated_p);

  // Reload to the same opening: back on the envelope where it left it, no extra damage.
  for (int i = 0; i < back; ++i) p.step(law, -dback, Vec3::Zero());
  EXPECT_NEAR(p.s.un, un_p, 1e-9 * u_nu);
  EXPECT_NEAR(p.s.fn, fn_p, 1e-9 * p.c.fn_max);
  EXPECT_EQ(p.s.damage, d_p);
  EXPECT_EQ(p.dissipated, dissipated_p);

  // Further opening resumes the monotonic softening line.
  for (int i = 0; i < 100; ++i) p.step(law, du, Vec3::Zero());
  EXPECT_GT(p.s.damage, d_p);
  EXPECT_NEAR(p.s.fn, tension_triangle(p.c, u_nu, p.s.un), 1e-9 * p.c.fn_max);
}

TEST(BilinearSoftening, CompressionIsUnlimitedAndElastic) {
  const BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  const Real closing = -100 * p.c.fn_max / p.c.kn;  // a hundred times the tensile strength
  for (int i = 0; i < 100; ++i) p.step(law, closing / 100, Vec3::Zero());
  EXPECT_NEAR(p.s.fn, p.c.kn * p.s.un, 1e-12 * p.c.kn * std::abs(p.s.un));
  EXPECT_NEAR(p.s.fn / (-100 * p.c.fn_max), 1.0, 1e-12);
  EXPECT_EQ(p.s.damage, 0.0);
  EXPECT_EQ(p.dissipated, 0.0);
  EXPECT_EQ(p.s.un_max, 0.0);
}

TEST(BilinearSoftening, ShearDamageLowersTheTensileCap) {
  const BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  const Real u_s0 = p.c.c_max / p.c.ks;
  const Real u_n0 = p.c.fn_max / p.c.kn;
  const Real u_nu = law.u_nu();
  const Vec3 dir = Vec3(1.0, 1.0, 0.0).normalized();
  // Shear to D_s = 0.3 (S3).
  const Real us_target = u_s0 + 0.3 * (law.u_su() - u_s0);
  for (int i = 0; i < 1000; ++i) p.step(law, 0.0, (us_target / 1000) * dir);
  EXPECT_NEAR(p.s.damage, 0.3, 1e-9);

  // Opening now: the cap is (1 - D) F_n,max (S5), reached before u_n0 so D_n is still 0 there.
  const Real du = u_nu / 4000;
  Real peak = 0;
  while (p.s.un < u_n0 + 0.5 * (u_nu - u_n0)) {
    p.step(law, du, Vec3::Zero());
    peak = std::max(peak, p.s.fn);
  }
  EXPECT_NEAR(peak / (0.7 * p.c.fn_max), 1.0, 0.01);
  // D = min(1, D_n + D_s) (S4): here D_n = 0.5 and D_s = 0.3.
  const Real d_n = (p.s.un_max - u_n0) / (u_nu - u_n0);
  EXPECT_NEAR(p.s.damage, d_n + 0.3, 1e-9);
  EXPECT_NEAR(p.s.fn, (1 - p.s.damage) * p.c.fn_max, 1e-9 * p.c.fn_max);
  EXPECT_NEAR(p.s.fs.norm(), (1 - p.s.damage) * p.c.c_max, 1e-9 * p.c.c_max);
  // Fully damaged once D_n reaches 0.7, before u_nu.
  while (p.s.un < u_n0 + 0.75 * (u_nu - u_n0)) p.step(law, du, Vec3::Zero());
  EXPECT_EQ(p.s.damage, 1.0);
  EXPECT_LE(p.s.fn, 0.0);
  EXPECT_EQ(p.s.fs.norm(), 0.0);
}

TEST(BilinearSoftening, ImposedDamageIsKeptAndCapsTension) {
  // A point may start damaged (e.g. a pre-cut notch): (S4) never lowers D below what it holds.
  const BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  p.s.damage = 0.5;
  const Real du = p.c.fn_max / p.c.kn / 100;
  Real peak = 0;
  for (int i = 0; i < 90; ++i) {
    p.step(law, du, Vec3::Zero());
    peak = std::max(peak, p.s.fn);
  }
  EXPECT_EQ(p.s.damage, 0.5);
  EXPECT_NEAR(peak / (0.5 * p.c.fn_max), 1.0, 1e-9);
}

TEST(BilinearSoftening, BrittleWhenFractureEnergyIsBelowTheElasticEnergy) {
  BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  const Real u_n0 = p.c.fn_max / p.c.kn;
  law.G_fn = 0.25 * law.sigma_nt * u_n0;  // u_nu = 0.5 u_n0 <= u_n0 (S2)
  ASSERT_LE(law.u_nu(), u_n0);
  const int steps = 2000;
  const Real du = 2 * u_n0 / steps;
  Real peak = 0;
  for (int i = 0; i < steps; ++i) {
    p.step(law, du, Vec3::Zero());
    peak = std::max(peak, p.s.fn);
    if (p.s.un > u_n0 * (1 + 1e-12)) {
      EXPECT_EQ(p.s.fn, 0.0);
      EXPECT_EQ(p.s.damage, 1.0);
    } else if (p.s.un < u_n0 * (1 - 1e-12)) {
      EXPECT_EQ(p.s.damage, 0.0);
      EXPECT_NEAR(p.s.fn, p.c.kn * p.s.un, 1e-9 * p.c.fn_max);
    }
  }
  EXPECT_NEAR(peak / p.c.fn_max, 1.0, 0.01);
  // All the elastic energy at the peak is released at once.
  EXPECT_NEAR(p.dissipated / (0.5 * p.c.fn_max * u_n0), 1.0, 0.01);
}

// A slow drift into opening and slip, with noise of 1% of the elastic range per step that
// unloads, reloads and recloses; each step optionally split into `substeps` equal parts.
Driver random_cyclic_path(const BilinearSoftening& law, int substeps) {
  Driver p{point_constants(law)};
  std::mt19937_64 rng(12345);
  std::normal_distribution<Real> g(0.0, 1.0);
  const Real dn = 0.01 * p.c.fn_max / p.c.kn;
  const Real ds = 0.01 * p.c.c_max / p.c.ks;
  for (int i = 0; i < 20000; ++i) {
    const Real dun = dn * (0.05 + g(rng));
    const Vec3 dus = ds * Vec3(0.05 + g(rng), g(rng), 0.0);
    for (int k = 0; k < substeps; ++k) {
      p.step(law, dun / substeps, dus / substeps);
      EXPECT_LE(p.s.damage, 1.0);
      EXPECT_LE(p.s.fn, (1 - p.s.damage) * p.c.fn_max * (1 + 1e-12));
      const Real fs_cap = (1 - p.s.damage) * p.c.c_max + law.mu_c * std::max<Real>(0, -p.s.fn);
      EXPECT_LE(p.s.fs.norm(), fs_cap * (1 + 1e-12));
    }
  }
  return p;
}

TEST(BilinearSoftening, RandomCyclicPathStaysInEnvelopeAndItsDissipationConverges) {
  const BilinearSoftening law = table2();
  // Driver::step checks on every step: damage never decreases, dissipation >= 0.
  const Driver coarse = random_cyclic_path(law, 1);
  const Driver fine = random_cyclic_path(law, 100);
  EXPECT_EQ(coarse.s.damage, 1.0);  // the path did go through softening to failure
  EXPECT_GT(coarse.friction, 0.0);  // and slid under compression
  // Reference: the trapezoidal ledger of the finely stepped path, which converges to the exact
  // work. The law's own dissipation agrees with it at both step sizes; at the coarse step it is
  // closer than the coarse trapezoid, which books closing-then-reopening steps as negative.
  const Real reference = fine.work - fine.elastic_energy();
  EXPECT_NEAR(fine.dissipated / reference, 1.0, 1e-3);
  EXPECT_NEAR(coarse.dissipated / reference, 1.0, 0.02);
  EXPECT_LT(std::abs(coarse.dissipated - reference),
            std::abs(coarse.work - coarse.elastic_energy() - reference));
}

TEST(ElasticLaw, AnyPathIsLinearWithoutDissipation) {
  const BilinearSoftening bl = table2();
  const Elastic law;
  Driver p{point_constants(bl)};
  std::mt19937_64 rng(7);
  std::normal_distribution<Real> g(0.0, 1.0);
  const Real step = 0.5 * bl.u_nu();  // large steps: far past any BL strength
  Real fn_peak = 0, u_peak = 0;
  for (int i = 0; i < 5000; ++i) {
    const Real dun = step * (0.01 + g(rng));
    const Vec3 dus = step * Vec3(g(rng), g(rng), g(rng));
    const LawResult r = p.step(law, dun, dus);
    EXPECT_EQ(r.dissipated, 0.0);
    EXPECT_FALSE(r.damage_grew);
    const Real u = std::max(std::abs(p.s.un), p.s.us.norm());
    u_peak = std::max(u_peak, u);
    const Real tol = 1e-12 * p.c.kn * u_peak;
    EXPECT_NEAR(p.s.fn, p.c.kn * p.s.un, tol);
    EXPECT_LT((p.s.fs + p.c.ks * p.s.us).norm(), tol);
    fn_peak = std::max(fn_peak, p.s.fn);
  }
  EXPECT_GT(fn_peak, 10 * p.c.fn_max);  // no strength limit
  EXPECT_EQ(p.s.damage, 0.0);
  EXPECT_LT(p.worst_step_balance, 1e-12 * p.c.kn * u_peak * u_peak);
  EXPECT_LT(std::abs(p.work - p.elastic_energy()), 1e-12 * p.c.kn * u_peak * u_peak);
}

// (S3)-(S4) make D a non-decreasing function of the two historical maxima, which themselves never
// decrease, so after any path D equals that function of the current maxima, to the bit. The law
// evaluates it only on steps that raise a maximum; a path that unloads, reloads and slips in
// every direction must still meet it at every step.
TEST(BilinearSoftening, DamageIsAlwaysTheFunctionOfTheCurrentMaxima) {
  const BilinearSoftening law = table2();
  Driver p{point_constants(law)};
  std::mt19937_64 rng(777);
  std::normal_distribution<Real> g(0.0, 1.0);
  const Real dn = 0.02 * p.c.fn_max / p.c.kn;
  const Real ds = 0.02 * p.c.c_max / p.c.ks;
  int partial = 0;
  for (int i = 0; i < 20000; ++i) {
    p.step(law, dn * (0.02 + g(rng)), Vec3(ds * (0.02 + g(rng)), ds * g(rng), 0.0));
    const LocalPointConstants& c = p.c;
    const Real d_n = c.kn * p.s.un_max > c.fn_max
                         ? softening_damage(p.s.un_max, c.fn_max / c.kn, law.u_nu())
                         : 0.0;
    const Real d_s = c.ks * c.ks * p.s.us_max_sq > c.c_max * c.c_max
                         ? softening_damage(std::sqrt(p.s.us_max_sq), c.c_max / c.ks, law.u_su())
                         : 0.0;
    ASSERT_EQ(p.s.damage, std::min<Real>(1, d_n + d_s)) << "step " << i;
    if (p.s.damage > 0 && p.s.damage < 1) ++partial;
  }
  EXPECT_GT(partial, 1000);  // the path spent long inside the softening range
}
