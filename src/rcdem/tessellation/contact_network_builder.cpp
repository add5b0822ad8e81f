#include "rcdem/tessellation/contact_network_builder.hpp"

#include <span>

#include "rcdem/contact/local_point_properties.hpp"
#include "rcdem/tessellation/facet_area_split.hpp"

namespace rcdem {

ContactNetwork build_contact_network(const Particles& p, const CellComplex& cc,
                                     const SpecimenGeometry& g, const ContactParameters& params,
                                     NetworkReport* report, BoundaryFaces* boundary) {
  ContactNetwork net;
  NetworkReport rep;
  net.point_begin.push_back(0);
  for (Index a = 0; a < cc.cell_count(); ++a) {
    for (Index f = cc.face_begin[a]; f < cc.face_begin[a + 1]; ++f) {
      const Index b = cc.face_neighbour[f];
      if (b < 0) {
        // voro++ numbers the container walls -1..-6 for x-, x+, y-, y+, z-, z+.
        // Plates act on the concrete; the bars' spheres are inside it.
        if (boundary && p.kind[a] != ParticleKind::Steel) {
          const std::span<const Vec3> raw(
              cc.vertices.data() + cc.vertex_begin[f],
              static_cast<std::size_t>(cc.vertex_begin[f + 1] - cc.vertex_begin[f]));
          const FacetSplit split = split_facet_area(raw);
          if (split.area > 0.0) {
            boundary->particle.push_back(a);
            boundary->face.push_back(static_cast<int>(-b - 1));
            boundary->area.push_back(split.area);
            boundary->centroid.push_back(split.centroid);
          }
        }
        continue;
      }
      if (b < a) continue;  // the pair was taken from b's side
      // Steel interface spheres: their facets are interface contacts, built apart (SPEC 8).
      if (p.kind[a] == ParticleKind::Steel || p.kind[b] == ParticleKind::Steel) continue;
      const Vec3& xa = p.position[a];
      const Vec3& xb = p.position[b];
      if (g.segment_crosses_notch(xa, xb)) {
        ++rep.facets_cut_by_notch;
        continue;
      }
      const Real d = (xb - xa).norm();
      const std::span<const Vec3> raw(
          cc.vertices.data() + cc.vertex_begin[f],
          static_cast<std::size_t>(cc.vertex_begin[f + 1] - cc.vertex_begin[f]));
      const std::vector<Vec3> verts = merge_close_vertices(raw, 1e-9 * d);
      const FacetSplit split = split_facet_area(verts);
      if (!(split.area > 1e-14 * d * d)) {
        ++rep.degenerate_facets;
        continue;
      }
      net.particle_a.push_back(a);
      net.particle_b.push_back(b);
      net.distance0.push_back(d);
      net.facet_area.push_back(split.area);
      auto add_point = [&](const Vec3& x, Real area) {
        const LocalPointConstants q = local_point_properties(params, area, d);
        net.point_position0.push_back(x);
        net.point_area.push_back(area);
        net.constants.push_back(q);
      };
      add_point(split.centroid, split.centroid_area);
      for (std::size_t v = 0; v < verts.size(); ++v) add_point(verts[v], split.vertex_area[v]);
      net.point_begin.push_back(static_cast<Index>(net.point_area.size()));
    }
  }
  if (report) *report = rep;
  return net;
}

}  // namespace rcdem
