// SPEC 2 asks for a homogeneous, isotropic point set after relaxation. Homogeneity: counts in
// sub-cubes fluctuate far less than for random points. Isotropy: the area-weighted fabric tensor of
// the contact normals, F = sum(A n n) / sum(A), is close to I/3.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "rcdem/specimens/specimen.hpp"

using namespace rcdem;

namespace {

Specimen cube(int iterations) {
  return build_specimen(parse_scenario(fmt::format(R"(
[specimen]
shape = "box"
size = [0.12, 0.12, 0.12]
[generation]
seed = 21
relaxation_iterations = {}
)",
                                                   iterations),
                                       "cube.toml"));
}

// Variance over mean of the particle counts in 20 mm sub-cubes of the interior: 1 for independent
// random points (Poisson), much less for a homogeneous packing.
Real count_variance_ratio(const Specimen& s) {
  const Real margin = 0.01, cell = 0.02;
  const int n = 5;  // (120 - 2 * 10) / 20
  std::vector<int> count(n * n * n, 0);
  for (const auto& x : s.particles.position) {
    int idx[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      idx[a] = static_cast<int>(std::floor((x[a] - margin) / cell));
      inside &= idx[a] >= 0 && idx[a] < n;
    }
    if (inside) ++count[(idx[2] * n + idx[1]) * n + idx[0]];
  }
  Real mean = 0.0, var = 0.0;
  for (int c : count) mean += c;
  mean /= count.size();
  for (int c : count) var += (c - mean) * (c - mean);
  var /= count.size();
  return var / mean;
}

Eigen::Vector3d fabric_eigenvalues(const Specimen& s) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  Real total = 0.0;
  const ContactNetwork& c = s.contacts;
  for (Index k = 0; k < c.contact_count(); ++k) {
    const Vec3 n = (s.particles.position[c.particle_b[k]] - s.particles.position[c.particle_a[k]])
                       .normalized();
    F += c.facet_area[k] * n * n.transpose();
    total += c.facet_area[k];
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(F / total).eigenvalues();
}

}  // namespace

TEST(PackingQuality, RelaxedPointSetIsHomogeneousAndIsotropic) {
  const Specimen s = cube(300);
  EXPECT_LT(count_variance_ratio(s), 0.35);
  const Eigen::Vector3d ev = fabric_eigenvalues(s);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(ev[i], 1.0 / 3.0, 0.01) << ev.transpose();
}

TEST(PackingQuality, RelaxationRemovesTheClusteringOfRandomPoints) {
  // Unrelaxed random points have close pairs (tiny, badly shaped facets); relaxation removes them.
  const Specimen raw = cube(0);
  const Specimen relaxed = cube(300);
  EXPECT_LT(raw.packing.min_distance_ratio, 0.5);
  EXPECT_GT(count_variance_ratio(raw), 0.7);
  EXPECT_LT(count_variance_ratio(relaxed), 0.35);
  EXPECT_GT(relaxed.packing.min_distance_ratio, 1.0);
  // Random points have many more facets per particle than a relaxed packing.
  const auto per_particle = [](const Specimen& s) {
    return static_cast<Real>(s.contacts.contact_count()) / static_cast<Real>(s.particles.size());
  };
  EXPECT_GT(per_particle(raw), per_particle(relaxed));
}
