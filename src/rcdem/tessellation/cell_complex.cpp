#include "rcdem/tessellation/cell_complex.hpp"

#include <cmath>
#include <voro++/voro++.hh>

#include "rcdem/core/error.hpp"

namespace rcdem {

namespace {

struct CellFaces {
  Real volume = 0.0;
  std::vector<int> neighbours;
  std::vector<int> face_vertices;  // voro++ layout: k, v_1..v_k, k, ...
  std::vector<double> vertices;    // global x, y, z
  std::vector<double> areas;
  bool computed = false;
};

// Block counts so that each voro++ block holds about five particles, voro++'s sweet spot.
void block_counts(const SpecimenGeometry& g, Index n, int counts[3]) {
  const Real h = std::cbrt(5.0 * g.box_volume() / static_cast<Real>(std::max<Index>(n, 1)));
  for (int a = 0; a < 3; ++a)
    counts[a] = std::max(1, static_cast<int>(std::lround(g.size()[a] / h)));
}

template <typename Container>
void compute_all(Container& con, std::vector<CellFaces>& cells) {
  voro::c_loop_all loop(con);
  voro::voronoicell_neighbor cell;
  if (!loop.start()) return;
  do {
    if (!con.compute_cell(cell, loop)) continue;
    const int id = loop.pid();
    double x, y, z;
    loop.pos(x, y, z);
    CellFaces& out = cells[static_cast<std::size_t>(id)];
    out.volume = cell.volume();
    cell.neighbors(out.neighbours);
    cell.face_vertices(out.face_vertices);
    cell.vertices(x, y, z, out.vertices);
    cell.face_areas(out.areas);
    out.computed = true;
  } while (loop.inc());
}

}  // namespace

CellComplex tessellate(const Particles& p, const SpecimenGeometry& g, TessellationKind kind) {
  const Index n = p.size();
  int nb[3];
  block_counts(g, n, nb);
  std::vector<CellFaces> cells(static_cast<std::size_t>(n));
  if (kind == TessellationKind::Voronoi) {
    voro::container con(g.lo.x(), g.hi.x(), g.lo.y(), g.hi.y(), g.lo.z(), g.hi.z(), nb[0], nb[1],
                        nb[2], false, false, false, 8);
    for (Index i = 0; i < n; ++i)
      con.put(static_cast<int>(i), p.position[i].x(), p.position[i].y(), p.position[i].z());
    compute_all(con, cells);
  } else {
    voro::container_poly con(g.lo.x(), g.hi.x(), g.lo.y(), g.hi.y(), g.lo.z(), g.hi.z(), nb[0],
                             nb[1], nb[2], false, false, false, 8);
    for (Index i = 0; i < n; ++i)
      con.put(static_cast<int>(i), p.position[i].x(), p.position[i].y(), p.position[i].z(),
              p.radius[i]);
    compute_all(con, cells);
  }

  CellComplex cc;
  cc.volume.resize(static_cast<std::size_t>(n));
  cc.face_begin.assign(1, 0);
  cc.vertex_begin.assign(1, 0);
  for (Index i = 0; i < n; ++i) {
    const CellFaces& c = cells[static_cast<std::size_t>(i)];
    // A radical tessellation can give a small particle inside a big one's power cell no cell at
    // all; a plain Voronoi cell of a point inside the box always exists.
    if (!c.computed)
      fail("particle {} at ({:.6g}, {:.6g}, {:.6g}) m has no {} cell", i, p.position[i].x(),
           p.position[i].y(), p.position[i].z(),
           kind == TessellationKind::Voronoi ? "Voronoi" : "radical");
    cc.volume[i] = c.volume;
    std::size_t k = 0;
    for (std::size_t f = 0; f < c.neighbours.size(); ++f) {
      const int order = c.face_vertices[k++];
      for (int v = 0; v < order; ++v) {
        const int vi = c.face_vertices[k++];
        cc.vertices.emplace_back(c.vertices[3 * vi], c.vertices[3 * vi + 1],
                                 c.vertices[3 * vi + 2]);
      }
      cc.face_neighbour.push_back(c.neighbours[f]);
      cc.face_area.push_back(c.areas[f]);
      cc.vertex_begin.push_back(static_cast<Index>(cc.vertices.size()));
    }
    cc.face_begin.push_back(static_cast<Index>(cc.face_neighbour.size()));
  }
  return cc;
}

}  // namespace rcdem
