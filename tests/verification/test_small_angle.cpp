// The small-angle series (core/small_angle.hpp) against libm, and the quaternion exponential that
// uses them (reinforcement/rigid_rotation.hpp) against Eigen's angle-axis rotation, on both sides
// of the threshold.
#include <gtest/gtest.h>

#include <cmath>

#include "rcdem/core/small_angle.hpp"
#include "rcdem/reinforcement/rigid_rotation.hpp"

namespace rcdem {

TEST(SmallAngle, SeriesEqualLibmToRoundingBelowTheThreshold) {
  for (const Real a : {1e-9, 1e-6, 3e-5, 1e-4, 5e-4, 1e-3, 1e-2, 0.025, 0.05, 0.0999}) {
    ASSERT_TRUE(is_small_angle(a * a));
    Real c, sinc;
    small_angle_cos_sinc(a * a, c, sinc);
    EXPECT_NEAR(c, std::cos(a), 2e-16) << a;
    EXPECT_NEAR(sinc * a, std::sin(a), 2e-16 * a) << a;
  }
  EXPECT_FALSE(is_small_angle(0.10001 * 0.10001));
}

TEST(SmallAngle, RotationExpIsTheRotationByTheVectorOnBothSidesOfTheThreshold) {
  const Vec3 axis = Vec3(0.3, -0.5, 0.8).normalized();
  for (const Real angle : {1e-7, 1e-4, 0.05, 0.19, 0.21, 0.3}) {  // threshold: |rot| = 0.2
    const Quat q = rotation_exp(angle * axis);
    const Quat ref(Eigen::AngleAxis<Real>(angle, axis));
    EXPECT_NEAR(q.w(), ref.w(), 2e-16) << angle;
    EXPECT_LT((q.vec() - ref.vec()).norm(), 2e-16 * angle + 1e-300) << angle;
    EXPECT_NEAR(q.norm(), 1.0, 2e-16) << angle;
  }
  const Quat zero = rotation_exp(Vec3::Zero());
  EXPECT_EQ(zero.w(), 1.0);
  EXPECT_EQ(zero.vec().norm(), 0.0);
}

}  // namespace rcdem
