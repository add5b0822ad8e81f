// Analytic check of the tessellation and the contact network on a simple cubic lattice, whose
// Voronoi cells are cubes: every facet is a square of side h, every cell volume h^3, and the
// contact stiffness per facet is E_bar h^2 / h = E_bar h (3).
#include <gtest/gtest.h>

#include "rcdem/contact/local_point_properties.hpp"
#include "rcdem/tessellation/cell_complex.hpp"
#include "rcdem/tessellation/contact_network_builder.hpp"

using namespace rcdem;

TEST(LatticeTessellation, CubicLatticeGivesSquareFacetsAndExactStiffness) {
  const int n = 6;
  const Real h = 0.01;
  SpecimenGeometry g;
  g.hi = Vec3::Constant(n * h);
  Particles p;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        p.add(Vec3((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h), 0.4 * h, ParticleKind::Mortar);
  for (const auto kind : {TessellationKind::Voronoi, TessellationKind::Radical}) {
    const CellComplex cc = tessellate(p, g, kind);
    for (Real v : cc.volume) EXPECT_NEAR(v / (h * h * h), 1.0, 1e-12);
    ContactParameters params;
    const ContactNetwork net = build_contact_network(p, cc, g, params);
    EXPECT_EQ(net.contact_count(), 3 * n * n * (n - 1));
    for (Index c = 0; c < net.contact_count(); ++c) {
      EXPECT_NEAR(net.facet_area[c] / (h * h), 1.0, 1e-12);
      EXPECT_EQ(net.points_of(c), 5);  // four corners and the centroid
      EXPECT_NEAR(net.distance0[c] / h, 1.0, 1e-12);
      Real kn = 0.0;
      for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) kn += net.constants[m].kn;
      EXPECT_NEAR(kn / (params.E_bar * h), 1.0, 1e-12);
      EXPECT_NEAR(net.point_area[net.point_begin[c]] / (h * h / 3.0), 1.0, 1e-12);
    }
  }
}
