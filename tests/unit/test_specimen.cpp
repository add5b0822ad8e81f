// The generated specimen and its VGCM-3D network on small boxes: volumes, facet symmetry, area
// split, local point properties, determinism and the packing's constraints (SPEC 2-3).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <span>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "rcdem/config/specimen_registry.hpp"
#include "rcdem/contact/local_point_properties.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/tessellation/cell_complex.hpp"
#include "small_scenarios.hpp"

using namespace rcdem;

namespace {

Real sum(const std::vector<Real>& v) {
  Real s = 0.0;
  for (Real x : v) s += x;
  return s;
}

}  // namespace

class SpecimenByTessellation : public ::testing::TestWithParam<std::string> {};

TEST_P(SpecimenByTessellation, CellVolumesSumToSpecimenVolume) {
  const Scenario sc = test::small_box(3, GetParam());
  const Specimen s = build_specimen(sc);
  ASSERT_GT(s.particles.size(), 100);
  EXPECT_NEAR(sum(s.particles.cell_volume) / s.geometry.volume(), 1.0, 1e-9);
  for (Real v : s.particles.cell_volume) EXPECT_GT(v, 0.0);
}

TEST_P(SpecimenByTessellation, FacetABEqualsFacetBA) {
  const Scenario sc = test::small_box(4, GetParam());
  const SpecimenGeometry g = specimen_geometry(sc);
  const Particles p = generate_packing(sc.generation, g);
  const CellComplex cc = tessellate(p, g, sc.tessellation);
  std::map<std::pair<Index, Index>, Index> face_of;
  for (Index a = 0; a < cc.cell_count(); ++a)
    for (Index f = cc.face_begin[a]; f < cc.face_begin[a + 1]; ++f)
      if (cc.face_neighbour[f] >= 0) face_of[{a, cc.face_neighbour[f]}] = f;
  Index checked = 0;
  for (const auto& [key, f] : face_of) {
    const auto it = face_of.find({key.second, key.first});
    ASSERT_NE(it, face_of.end()) << "facet " << key.first << "-" << key.second << " is one-sided";
    const Index h = it->second;
    EXPECT_NEAR(cc.face_area[f] / cc.face_area[h], 1.0, 1e-9);
    // Same polygon: same vertex set (order reversed, start anywhere).
    const Index nf = cc.vertex_begin[f + 1] - cc.vertex_begin[f];
    ASSERT_EQ(nf, cc.vertex_begin[h + 1] - cc.vertex_begin[h]);
    for (Index i = cc.vertex_begin[f]; i < cc.vertex_begin[f + 1]; ++i) {
      Real best = 1e30;
      for (Index j = cc.vertex_begin[h]; j < cc.vertex_begin[h + 1]; ++j)
        best = std::min(best, (cc.vertices[i] - cc.vertices[j]).norm());
      EXPECT_LT(best, 1e-12);
    }
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST_P(SpecimenByTessellation, LocalPointAreasSumToFacetArea) {
  const Specimen s = build_specimen(test::small_box(5, GetParam()));
  const ContactNetwork& c = s.contacts;
  ASSERT_GT(c.contact_count(), 500);
  for (Index k = 0; k < c.contact_count(); ++k) {
    Real a = 0.0;
    for (Index m = c.point_begin[k]; m < c.point_begin[k + 1]; ++m) a += c.point_area[m];
    EXPECT_NEAR(a / c.facet_area[k], 1.0, 1e-12);
    // A facet has at least three vertices, plus its centroid.
    EXPECT_GE(c.points_of(k), 4);
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, SpecimenByTessellation, ::testing::Values("voronoi", "radical"));

TEST(Specimen, LocalPointPropertiesFollowEquations3To6) {
  const Scenario sc = test::small_box(6);
  const Specimen s = build_specimen(sc);
  const ContactNetwork& c = s.contacts;
  const ContactParameters& p = sc.contact;
  for (Index k = 0; k < c.contact_count(); k += 7) {
    const Real d = c.distance0[k];
    EXPECT_NEAR(
        d, (s.particles.position[c.particle_b[k]] - s.particles.position[c.particle_a[k]]).norm(),
        1e-15);
    for (Index m = c.point_begin[k]; m < c.point_begin[k + 1]; ++m) {
      const Real A = c.point_area[m];
      EXPECT_DOUBLE_EQ(c.constants[m].kn, p.E_bar * A / d);
      EXPECT_DOUBLE_EQ(c.constants[m].ks, p.alpha * p.E_bar * A / d);
      EXPECT_DOUBLE_EQ(c.constants[m].fn_max, p.sigma_nt * A);
      EXPECT_DOUBLE_EQ(c.constants[m].c_max, p.tau * A);
    }
  }
}

TEST(Specimen, LocalPointsLieOnTheFacetPlaneHalfwayForVoronoi) {
  // A plain Voronoi facet is the perpendicular bisector plane of the two centres.
  const Specimen s = build_specimen(test::small_box(7));
  const ContactNetwork& c = s.contacts;
  for (Index k = 0; k < c.contact_count(); ++k) {
    const Vec3& a = s.particles.position[c.particle_a[k]];
    const Vec3& b = s.particles.position[c.particle_b[k]];
    const Vec3 n = (b - a).normalized();
    const Vec3 mid = 0.5 * (a + b);
    for (Index m = c.point_begin[k]; m < c.point_begin[k + 1]; ++m)
      ASSERT_NEAR((c.point_position0[m] - mid).dot(n), 0.0, 1e-12);
  }
}

TEST(Specimen, PackingHonoursContentPorosityAndMinimumDistances) {
  const Scenario sc = test::small_box(8);
  const Specimen s = build_specimen(sc);
  const Real V = s.geometry.volume();
  const auto& g = sc.generation;
  // Aggregate content within one aggregate sphere of the target; porosity within one mortar sphere.
  const Real one_agg = kPi / 6.0 * std::pow(g.aggregate_d_max, 3) / V;
  EXPECT_NEAR(s.packing.aggregate_volume / V, g.aggregate_content / g.aggregate_density, one_agg);
  EXPECT_NEAR(s.packing.porosity, g.porosity, kPi / 6.0 * std::pow(g.mortar_d_max, 3) / V);
  EXPECT_GE(s.packing.min_distance_ratio, g.min_distance_factor);
  EXPECT_GE(s.packing.min_face_ratio, g.min_distance_factor * (1.0 - 1e-12));
  for (Index i = 0; i < s.particles.size(); ++i) {
    const Real r = s.particles.radius[i];
    const ParticleKind k = s.particles.kind[i];
    if (k == ParticleKind::Aggregate) {
      EXPECT_GE(2 * r, g.aggregate_d_min);
      EXPECT_LE(2 * r, g.aggregate_d_max);
    } else {
      EXPECT_GE(2 * r, g.mortar_d_min);
      EXPECT_LE(2 * r, g.mortar_d_max);
    }
  }
}

TEST(Specimen, SameSeedSamePackingOtherSeedDifferent) {
  const Specimen a = build_specimen(test::small_box(11));
  const Specimen b = build_specimen(test::small_box(11));
  const Specimen c = build_specimen(test::small_box(12));
  ASSERT_EQ(a.particles.size(), b.particles.size());
  for (Index i = 0; i < a.particles.size(); ++i)
    ASSERT_EQ(a.particles.position[i], b.particles.position[i]);
  ASSERT_EQ(a.contacts.point_area, b.contacts.point_area);
  ASSERT_EQ(a.contacts.particle_a, b.contacts.particle_a);
  EXPECT_NE(a.particles.position[0], c.particles.position[0]);
}

#if defined(_OPENMP)
TEST(Specimen, PackingDoesNotDependOnThreadCount) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  const Specimen a = build_specimen(test::small_box(13));
  omp_set_num_threads(2);
  const Specimen b = build_specimen(test::small_box(13));
  omp_set_num_threads(before);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  for (Index i = 0; i < a.particles.size(); ++i)
    ASSERT_EQ(a.particles.position[i], b.particles.position[i]);
}
#endif

TEST(Specimen, NotchCutsContactsAcrossIt) {
  const Scenario sc = parse_scenario(R"(
[specimen]
shape = "beam"
size = [0.12, 0.04, 0.05]
notch_depth = 0.02
notch_width = 0.003
[generation]
relaxation_iterations = 60
)",
                                     "notched.toml");
  const Specimen s = build_specimen(sc);
  EXPECT_GT(s.network.facets_cut_by_notch, 5);
  const Real xc = 0.06;
  for (Index i = 0; i < s.particles.size(); ++i)
    EXPECT_FALSE(s.geometry.in_notch(s.particles.position[i]));
  for (Index k = 0; k < s.contacts.contact_count(); ++k) {
    const Vec3& a = s.particles.position[s.contacts.particle_a[k]];
    const Vec3& b = s.particles.position[s.contacts.particle_b[k]];
    if ((a.x() - xc) * (b.x() - xc) >= 0.0) continue;
    // A contact that crosses the notch plane does so above the notch tip.
    const Real t = (xc - a.x()) / (b.x() - a.x());
    EXPECT_GE(a.z() + t * (b.z() - a.z()), 0.02);
  }
}
