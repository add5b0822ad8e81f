#include "rcdem/io/specimen_output.hpp"

#include <algorithm>

#include "rcdem/io/vtu_writer.hpp"

namespace rcdem::io {

nlohmann::ordered_json specimen_summary(const Scenario& scenario, const Specimen& s) {
  const Particles& p = s.particles;
  const ContactNetwork& c = s.contacts;
  Real cell_sum = 0.0;
  for (Real v : p.cell_volume) cell_sum += v;
  const Real n = static_cast<Real>(p.size());
  nlohmann::ordered_json j;
  j["scenario"] = scenario.source.string();
  j["seed"] = scenario.generation.seed;
  j["particles"] = {{"aggregate", p.count(ParticleKind::Aggregate)},
                    {"mortar", p.count(ParticleKind::Mortar)},
                    {"steel", p.count(ParticleKind::Steel)},
                    {"total", p.size()}};
  Index interface_contacts = 0, interface_points = 0, cylinders = 0;
  for (const auto& ic : s.interfaces) {
    interface_contacts += ic.net.contact_count();
    interface_points += ic.net.point_count();
  }
  for (const auto& b : s.bars) cylinders += static_cast<Index>(b.cylinders.size());
  // All contacts, the steel-concrete interface included (as the paper counts them).
  j["contacts"] = c.contact_count() + interface_contacts;
  j["local_points"] = c.point_count() + interface_points;
  j["concrete_contacts"] = c.contact_count();
  j["interface_contacts"] = interface_contacts;
  j["bars"] = s.bars.size();
  j["cylinders"] = cylinders;
  if (!s.ties.empty()) j["bar_ties"] = s.ties.size();  // where two bars touch
  // The paper counts contacts per particle as contacts / particles (153,165 / 23,855 = 6.4).
  j["contacts_per_particle"] = n > 0 ? static_cast<Real>(c.contact_count()) / n : 0.0;
  j["local_points_per_contact"] = c.contact_count() > 0 ? static_cast<Real>(c.point_count()) /
                                                              static_cast<Real>(c.contact_count())
                                                        : 0.0;
  j["porosity"] = s.packing.porosity;
  j["aggregate_mass_per_m3"] =
      s.packing.aggregate_volume * scenario.generation.aggregate_density / s.geometry.volume();
  j["specimen_volume"] = s.geometry.volume();
  j["cell_volume_sum"] = cell_sum;
  j["min_centre_distance_over_radius"] = s.packing.min_distance_ratio;
  j["min_face_distance_over_radius"] = s.packing.min_face_ratio;
  if (!s.bars.empty()) j["min_bar_clearance_over_radius"] = s.packing.min_bar_ratio;
  j["facets_cut_by_notch"] = s.network.facets_cut_by_notch;
  j["degenerate_facets_dropped"] = s.network.degenerate_facets;
  return j;
}

void write_particles_vtu(const std::filesystem::path& path, const Specimen& s, bool binary) {
  const Particles& p = s.particles;
  UnstructuredGrid grid;
  grid.points = p.position;
  grid.add_vertex_cells();
  grid.add_point_data("radius", p.radius);
  std::vector<std::int32_t> kind(p.kind.size());
  for (std::size_t i = 0; i < kind.size(); ++i) kind[i] = static_cast<std::int32_t>(p.kind[i]);
  grid.add_point_data("kind", kind);
  grid.add_point_data("cell_volume", p.cell_volume);
  std::vector<std::int64_t> id(p.kind.size());
  for (std::size_t i = 0; i < id.size(); ++i) id[i] = static_cast<std::int64_t>(i);
  grid.add_point_data("id", id);
  write_vtu(path, grid, binary ? VtuEncoding::Binary : VtuEncoding::Ascii);
}

std::vector<Index> facet_order(const ContactNetwork& contacts) {
  std::vector<Index> order(static_cast<std::size_t>(contacts.contact_count()));
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<Index>(k);
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) {
    return contacts.points_of(a) < contacts.points_of(b);
  });
  return order;
}

void write_facets_vtu(const std::filesystem::path& path, const Specimen& s, bool binary) {
  const ContactNetwork& c = s.contacts;
  UnstructuredGrid grid;
  std::vector<std::int64_t> ids;
  std::vector<Real> area;
  std::vector<std::int32_t> points;
  std::vector<std::int64_t> pa, pb, contact;
  for (const Index k : facet_order(c)) {
    contact.push_back(k);
    ids.clear();
    // The centroid is the first local point; the polygon is the vertices after it.
    for (Index m = c.point_begin[k] + 1; m < c.point_begin[k + 1]; ++m) {
      ids.push_back(static_cast<std::int64_t>(grid.points.size()));
      grid.points.push_back(c.point_position0[m]);
    }
    grid.add_polygon(ids);
    area.push_back(c.facet_area[k]);
    points.push_back(static_cast<std::int32_t>(c.points_of(k)));
    pa.push_back(c.particle_a[k]);
    pb.push_back(c.particle_b[k]);
  }
  grid.add_cell_data("area", area);
  grid.add_cell_data("local_points", points);
  grid.add_cell_data("particle_a", pa);
  grid.add_cell_data("particle_b", pb);
  grid.add_cell_data("contact", contact);
  write_vtu(path, grid, binary ? VtuEncoding::Binary : VtuEncoding::Ascii);
}

}  // namespace rcdem::io
