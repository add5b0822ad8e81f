#include "rcdem/io/run_output.hpp"

#include <fmt/format.h>

#include "rcdem/contact/contact_kinematics.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/io/vtu_writer.hpp"

namespace rcdem::io {

namespace fs = std::filesystem;

std::vector<Real> particle_damage(const Simulation& sim) {
  const ContactNetwork& net = sim.specimen().contacts;
  const auto& pts = sim.contacts().point;
  const auto n = static_cast<std::size_t>(sim.bodies().size());
  std::vector<Real> sum(n, 0.0), area(n, 0.0);
  for (Index c = 0; c < net.contact_count(); ++c) {
    Real d = 0.0, a = 0.0;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
      d += pts[m].damage * net.point_area[m];
      a += net.point_area[m];
    }
    for (Index i : {net.particle_a[c], net.particle_b[c]}) {
      sum[i] += d;
      area[i] += a;
    }
  }
  for (std::size_t i = 0; i < n; ++i) sum[i] = area[i] > 0.0 ? sum[i] / area[i] : 0.0;
  return sum;
}

Vec3 face_strains(const Simulation& sim) {
  // Like gauges on the specimen: the mean displacement of the particles on each face, along the
  // face's normal; high face minus low face, over the specimen's length.
  const BoundaryFaces& f = sim.specimen().boundary;
  const Bodies& b = sim.bodies();
  Real sum[6] = {0, 0, 0, 0, 0, 0}, area[6] = {0, 0, 0, 0, 0, 0};
  for (Index k = 0; k < f.size(); ++k) {
    const int face = f.face[k];
    const Index i = f.particle[k];
    sum[face] += f.area[k] * (b.position[i][face / 2] - b.position0[i][face / 2]);
    area[face] += f.area[k];
  }
  const Vec3 size = sim.specimen().geometry.size();
  Vec3 e = Vec3::Zero();
  for (int a = 0; a < 3; ++a)
    if (area[2 * a] > 0.0 && area[2 * a + 1] > 0.0)
      e[a] = (sum[2 * a + 1] / area[2 * a + 1] - sum[2 * a] / area[2 * a]) / size[a];
  return e;
}

SnapshotWriter::SnapshotWriter(fs::path dir, bool binary, bool facets)
    : dir_(std::move(dir)), binary_(binary), facets_(facets) {
  fs::create_directories(dir_ / "snapshots");
}

void SnapshotWriter::write(const Simulation& sim) {
  const Bodies& b = sim.bodies();
  const Particles& p = sim.specimen().particles;
  const VtuEncoding enc = binary_ ? VtuEncoding::Binary : VtuEncoding::Ascii;
  const std::string stamp = fmt::format("{:09d}", sim.steps());
  {
    UnstructuredGrid g;
    g.points = b.position;
    g.add_vertex_cells();
    g.add_point_data("radius", p.radius);
    std::vector<std::int32_t> kind(p.kind.size());
    for (std::size_t i = 0; i < kind.size(); ++i) kind[i] = static_cast<std::int32_t>(p.kind[i]);
    g.add_point_data("kind", kind);
    std::vector<Vec3> disp(b.position.size());
    for (std::size_t i = 0; i < disp.size(); ++i) disp[i] = b.position[i] - b.position0[i];
    g.add_point_data("displacement", disp);
    g.add_point_data("velocity", b.velocity);
    g.add_point_data("damage", particle_damage(sim));
    const std::string name = "particles_" + stamp + ".vtu";
    write_vtu(dir_ / "snapshots" / name, g, enc);
    particle_series_.emplace_back(sim.time(), "snapshots/" + name);
    write_pvd(dir_ / "particles.pvd", particle_series_);
  }
  if (!facets_) return;
  const ContactNetwork& net = sim.specimen().contacts;
  const auto& pts = sim.contacts().point;
  UnstructuredGrid g;
  std::vector<Real> damage, opening;
  std::vector<std::uint8_t> broken;
  std::vector<std::int64_t> ids;
  for (Index c = 0; c < net.contact_count(); ++c) {
    const Index ia = net.particle_a[c], ib = net.particle_b[c];
    const Eigen::Matrix3d ra = b.orientation[ia].toRotationMatrix();
    const Eigen::Matrix3d rb = b.orientation[ib].toRotationMatrix();
    const Vec3& n = sim.contacts().normal[c];
    ids.clear();
    Real d = 0.0, a = 0.0;
    bool all_broken = true;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
      d += pts[m].damage * net.point_area[m];
      a += net.point_area[m];
      all_broken &= pts[m].damage >= 1.0;
      if (m == net.point_begin[c]) continue;  // the centroid is not a polygon vertex
      const PointKinematics k =
          point_kinematics(net.point_position0[m], b.position[ia], b.position0[ia], ra,
                           b.position[ib], b.position0[ib], rb, n);
      ids.push_back(static_cast<std::int64_t>(g.points.size()));
      g.points.push_back(k.position);
    }
    g.add_polygon(ids);
    damage.push_back(a > 0.0 ? d / a : 0.0);
    opening.push_back(pts[net.point_begin[c]].un);
    broken.push_back(all_broken ? 1 : 0);
  }
  g.add_cell_data("damage", damage);
  g.add_cell_data("opening", opening);
  g.add_cell_data("broken", broken);
  const std::string name = "facets_" + stamp + ".vtu";
  write_vtu(dir_ / "snapshots" / name, g, enc);
  facet_series_.emplace_back(sim.time(), "snapshots/" + name);
  write_pvd(dir_ / "facets.pvd", facet_series_);
}

History::History(const Simulation& sim, std::string control) : control_(std::move(control)) {
  columns_ = {"step", "time_s"};
  for (const auto& p : sim.plates()) {
    columns_.push_back(p.name + "_displacement_m");
    columns_.push_back(p.name + "_force_N");
  }
  for (const char* c :
       {"strain_x", "strain_y", "strain_z", "load_N", "kinetic_J", "strain_J",
        "dissipated_damage_J", "dissipated_friction_J", "dissipated_damping_J", "external_work_J",
        "energy_balance_error", "damaged_points", "broken_points"})
    columns_.emplace_back(c);
}

void History::record(const Simulation& sim) {
  std::vector<double> row = {static_cast<double>(sim.steps()), sim.time()};
  for (const auto& p : sim.plates()) {
    row.push_back(p.displacement);
    row.push_back(p.force[p.axis]);
  }
  const Vec3 strain = face_strains(sim);
  row.insert(row.end(), {strain.x(), strain.y(), strain.z()});
  const Plate* control = sim.find_plate(control_);
  const Energy& e = sim.energy();
  row.insert(row.end(),
             {control ? control->load() : 0.0, e.kinetic, e.strain, e.damage, e.friction, e.damping,
              e.external_work, e.balance_error(), static_cast<double>(sim.damaged_points()),
              static_cast<double>(sim.broken_points())});
  rows_.push_back(std::move(row));
}

void History::write(const fs::path& path) const {
  std::string out;
  for (std::size_t i = 0; i < columns_.size(); ++i) out += (i ? "," : "") + columns_[i];
  out += "\n";
  for (const auto& row : rows_) {
    for (std::size_t i = 0; i < row.size(); ++i)
      out += fmt::format("{}{:.10g}", i ? "," : "", row[i]);
    out += "\n";
  }
  write_file_atomically(path, out);
}

}  // namespace rcdem::io
