#include <gtest/gtest.h>

#include <cmath>

#include "rcdem/packing/grading.hpp"

using namespace rcdem;

namespace {

void check_distribution(const DiameterDistribution& d) {
  Rng rng(7);
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const Real x = d.sample(rng);
    ASSERT_GE(x, d.d_min);
    ASSERT_LE(x, d.d_max);
    sum += kPi / 6.0 * x * x * x;
  }
  // Monte Carlo mean against the closed form, to a few standard errors.
  EXPECT_NEAR(sum / n / d.mean_volume(), 1.0, 3e-3);
}

}  // namespace

TEST(Grading, UniformMeanVolumeMatchesClosedForm) {
  check_distribution({Grading::Uniform, 0.008, 0.012, 0.5});
  // The paper's mortar: E[d^3] = (9^4 - 8^4) / 4 mm^3.
  const DiameterDistribution m{Grading::Uniform, 0.008, 0.009, 0.5};
  EXPECT_NEAR(m.mean_volume() / (kPi / 6.0 * 616.25e-9), 1.0, 1e-12);
}

TEST(Grading, FullerMeanVolumeMatchesClosedForm) {
  check_distribution({Grading::Fuller, 0.008, 0.012, 0.5});
  check_distribution({Grading::Fuller, 0.004, 0.016, 0.45});
}

TEST(Grading, FullerFavoursSmallDiameters) {
  const DiameterDistribution f{Grading::Fuller, 0.008, 0.012, 0.5};
  const DiameterDistribution u{Grading::Uniform, 0.008, 0.012, 0.5};
  EXPECT_LT(f.mean_volume(), u.mean_volume());
}

TEST(Rng, SameSeedSameSequenceInUnitInterval) {
  Rng a(42), b(42), c(43);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const double x = a.uniform();
    ASSERT_EQ(x, b.uniform());
    ASSERT_GE(x, 0.0);
    ASSERT_LT(x, 1.0);
    differs |= (x != c.uniform());
  }
  EXPECT_TRUE(differs);
}
