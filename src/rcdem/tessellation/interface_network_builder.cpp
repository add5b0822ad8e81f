#include "rcdem/tessellation/interface_network_builder.hpp"

#include <map>
#include <span>

#include "rcdem/contact/local_point_properties.hpp"
#include "rcdem/tessellation/facet_area_split.hpp"

namespace rcdem {

ContactParameters interface_parameters(const ContactParameters& concrete, const BarSettings& bar) {
  ContactParameters p = concrete;
  if (bar.interface == InterfaceLaw::NL_B) {
    p.sigma_nt *= 0.5;
    p.tau *= 0.5;
  }
  p.sigma_nt *= bar.interface_strength_scale;
  p.tau *= bar.interface_strength_scale;
  p.G_fn *= bar.interface_energy_scale;
  p.G_fs *= bar.interface_energy_scale;
  return p;
}

namespace {

struct Merge {
  Real total_area = 0.0;
  Real largest_area = 0.0;
  std::vector<Vec3> largest;  // the largest facet's vertices
  Index nearest = -1;         // the nearest steel particle
  Real nearest_distance = 0.0;
};

}  // namespace

std::vector<InterfaceContacts> build_interface_contacts(const Particles& p, const CellComplex& cc,
                                                        const SteelSpheres& steel,
                                                        const std::vector<BarSettings>& bars,
                                                        const ContactParameters& concrete) {
  // (concrete particle, bar) -> merged facets; ordered, so the contacts come out the same always.
  std::map<std::pair<Index, int>, Merge> merged;
  for (Index a = 0; a < steel.first; ++a) {
    for (Index f = cc.face_begin[a]; f < cc.face_begin[a + 1]; ++f) {
      const Index b = cc.face_neighbour[f];
      if (b < steel.first) continue;  // a specimen face or another concrete particle
      const std::span<const Vec3> raw(
          cc.vertices.data() + cc.vertex_begin[f],
          static_cast<std::size_t>(cc.vertex_begin[f + 1] - cc.vertex_begin[f]));
      const Real d = (p.position[b] - p.position[a]).norm();
      std::vector<Vec3> verts = merge_close_vertices(raw, 1e-9 * d);
      const FacetSplit split = split_facet_area(verts);
      if (!(split.area > 1e-14 * d * d)) continue;
      Merge& m = merged[{a, steel.bar[b - steel.first]}];
      m.total_area += split.area;
      if (split.area > m.largest_area) {
        m.largest_area = split.area;
        m.largest = std::move(verts);
      }
      if (m.nearest < 0 || d < m.nearest_distance) {
        m.nearest = b;
        m.nearest_distance = d;
      }
    }
  }
  std::vector<InterfaceContacts> out(bars.size());
  for (std::size_t k = 0; k < bars.size(); ++k) {
    out[k].bar = static_cast<int>(k);
    out[k].net.point_begin.push_back(0);
  }
  for (const auto& [key, m] : merged) {
    InterfaceContacts& ic = out[static_cast<std::size_t>(key.second)];
    ContactNetwork& net = ic.net;
    const ContactParameters params =
        interface_parameters(concrete, bars[static_cast<std::size_t>(key.second)]);
    const Index s = m.nearest;
    net.particle_a.push_back(key.first);
    net.particle_b.push_back(steel.body[s - steel.first]);
    net.distance0.push_back(m.nearest_distance);
    net.facet_area.push_back(m.total_area);
    ic.anchor0.push_back(p.position[s]);
    const FacetSplit split = split_facet_area(m.largest);
    const Real scale = m.total_area / m.largest_area;
    auto add = [&](const Vec3& x, Real area) {
      net.point_position0.push_back(x);
      net.point_area.push_back(area);
      net.constants.push_back(local_point_properties(params, area, m.nearest_distance));
    };
    add(split.centroid, scale * split.centroid_area);
    for (std::size_t v = 0; v < m.largest.size(); ++v)
      add(m.largest[v], scale * split.vertex_area[v]);
    net.point_begin.push_back(static_cast<Index>(net.point_area.size()));
  }
  return out;
}

}  // namespace rcdem
