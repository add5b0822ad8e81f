#include "rcdem/run/run_output.hpp"

#include <fmt/format.h>

#include "rcdem/contact/contact_kinematics.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/io/specimen_output.hpp"
#include "rcdem/io/vtu_writer.hpp"

namespace rcdem::io {

namespace fs = std::filesystem;

std::vector<Real> particle_damage(const Simulation& sim) {
  const ContactNetwork& net = sim.specimen().contacts;
  const PointDamage damage = sim.point_damage();  // current without a catch-up
  const auto n = static_cast<std::size_t>(sim.bodies().size());
  std::vector<Real> sum(n, 0.0), area(n, 0.0);
  for (Index c = 0; c < net.contact_count(); ++c) {
    Real d = 0.0, a = 0.0;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
      d += damage[static_cast<std::size_t>(m)] * net.point_area[m];
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

void SnapshotWriter::write_bars(const Simulation& sim, const std::string& stamp, VtuEncoding enc) {
  // Each cylinder as a line between its two ends, with what its nodes carry (the larger of its
  // two nodes' values; an end cylinder has one node).
  const Bodies& b = sim.bodies();
  const Index first = sim.concrete_count();
  const auto ncyl = static_cast<std::size_t>(b.size() - first);
  std::vector<Real> axial(ncyl, 0.0), moment(ncyl, 0.0), stress(ncyl, 0.0);
  std::vector<std::uint8_t> yielded(ncyl, 0);
  std::vector<std::int32_t> bar(ncyl, 0);
  const auto& refs = sim.nodes();
  for (std::size_t j = 0; j < refs.size(); ++j) {
    const NodeState& st = sim.node_states()[j];
    const Real area =
        0.25 * kPi *
        std::pow(sim.specimen().bars[static_cast<std::size_t>(refs[j].bar)].diameter, 2);
    for (const Index body : {refs[j].body_a, refs[j].body_b}) {
      const auto c = static_cast<std::size_t>(body - first);
      if (std::abs(st.axial_force) > std::abs(axial[c])) axial[c] = st.axial_force;
      moment[c] = std::max(moment[c], st.bending_moment.norm());
      stress[c] = axial[c] / area;
      yielded[c] |= st.yielded ? 1 : 0;
      bar[c] = refs[j].bar;
    }
  }
  UnstructuredGrid g;
  std::size_t c = 0;
  std::vector<Real> radius;  // for ParaView's Tube filter (radius varying by this array)
  for (const Bar& br : sim.specimen().bars)
    for (const auto& cyl : br.cylinders) {
      radius.push_back(0.5 * br.diameter);
      const Index body = first + static_cast<Index>(c);
      const Vec3 axis = b.orientation[body] * cyl.axis;
      const auto id = static_cast<std::int64_t>(g.points.size());
      g.points.push_back(b.position[body] - 0.5 * cyl.length * axis);
      g.points.push_back(b.position[body] + 0.5 * cyl.length * axis);
      g.add_line(id, id + 1);
      ++c;
    }
  g.add_cell_data("axial_force", axial);
  g.add_cell_data("axial_stress", stress);
  g.add_cell_data("bending_moment", moment);
  g.add_cell_data("yielded", yielded);
  g.add_cell_data("bar", bar);
  g.add_cell_data("radius", radius);
  emit(g, "bars", stamp, sim.time(), enc, bar_series_);
}

// snapshots/KIND_STEP.vtu, and KIND.pvd listing the series so far.
void SnapshotWriter::emit(const UnstructuredGrid& g, const std::string& kind,
                          const std::string& stamp, double time, VtuEncoding enc,
                          std::vector<std::pair<double, std::string>>& series) {
  const std::string name = kind + "_" + stamp + ".vtu";
  write_vtu(dir_ / "snapshots" / name, g, enc);
  series.emplace_back(time, "snapshots/" + name);
  write_pvd(dir_ / (kind + ".pvd"), series);
}

SnapshotWriter::SnapshotWriter(fs::path dir, bool binary, bool facets)
    : dir_(std::move(dir)), binary_(binary), facets_(facets) {
  fs::create_directories(dir_ / "snapshots");
}

void SnapshotWriter::write(const Simulation& sim) {
  // Every point current (a distributed run's: on this rank) before the first array reads them.
  sim.catch_up_condensed_points();
  const Bodies& b = sim.bodies();
  const Particles& p = sim.specimen().particles;
  const VtuEncoding enc = binary_ ? VtuEncoding::Binary : VtuEncoding::Ascii;
  const std::string stamp = fmt::format("{:09d}", sim.steps());
  {
    // The concrete particles (bodies [0, concrete)); the bars follow in bars.vtu.
    const auto nc = static_cast<std::size_t>(sim.concrete_count());
    UnstructuredGrid g;
    g.points.assign(b.position.begin(), b.position.begin() + static_cast<std::ptrdiff_t>(nc));
    g.add_vertex_cells();
    g.add_point_data(
        "radius",
        std::vector<Real>(p.radius.begin(), p.radius.begin() + static_cast<std::ptrdiff_t>(nc)));
    std::vector<std::int32_t> kind(nc);
    for (std::size_t i = 0; i < nc; ++i) kind[i] = static_cast<std::int32_t>(p.kind[i]);
    g.add_point_data("kind", kind);
    std::vector<std::int64_t> id(nc);
    for (std::size_t i = 0; i < nc; ++i) id[i] = static_cast<std::int64_t>(i);
    g.add_point_data("id", id);  // as in generate's particles.vtu
    std::vector<Vec3> disp(nc), vel(nc);
    for (std::size_t i = 0; i < nc; ++i) {
      disp[i] = b.position[i] - b.position0[i];
      vel[i] = b.velocity[i];
    }
    g.add_point_data("displacement", disp);
    g.add_point_data("velocity", vel);
    std::vector<Real> damage = particle_damage(sim);
    damage.resize(nc);
    g.add_point_data("damage", damage);
    emit(g, "particles", stamp, sim.time(), enc, particle_series_);
  }
  if (!sim.nodes().empty()) write_bars(sim, stamp, enc);
  if (!facets_) return;
  const ContactNetwork& net = sim.specimen().contacts;
  // Read once: every call of contacts() checks for condensed contacts to bring up to date.
  const ContactState& cs = sim.contacts();
  const PointDamage point_damage = cs.point.damage();
  UnstructuredGrid g;
  std::vector<Real> damage, opening;
  std::vector<std::uint8_t> broken;
  std::vector<std::int64_t> ids, particle_a, particle_b, contact;
  if (facet_order_.empty()) facet_order_ = facet_order(net);
  for (const Index c : facet_order_) {
    const Index ia = net.particle_a[c], ib = net.particle_b[c];
    contact.push_back(c);
    particle_a.push_back(ia);
    particle_b.push_back(ib);
    const Eigen::Matrix3d ra = b.orientation[ia].toRotationMatrix();
    const Eigen::Matrix3d rb = b.orientation[ib].toRotationMatrix();
    const Vec3& n = cs.normal[c];
    ids.clear();
    Real d = 0.0, a = 0.0;
    bool all_broken = true;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
      d += point_damage[static_cast<std::size_t>(m)] * net.point_area[m];
      a += net.point_area[m];
      all_broken &= point_damage[static_cast<std::size_t>(m)] >= 1.0;
      if (m == net.point_begin[c]) continue;  // the centroid is not a polygon vertex
      const PointKinematics k =
          point_kinematics(net.point_position0[m], b.position[ia], b.position0[ia], ra,
                           b.position[ib], b.position0[ib], rb, n);
      ids.push_back(static_cast<std::int64_t>(g.points.size()));
      g.points.push_back(k.position);
    }
    g.add_polygon(ids);
    damage.push_back(a > 0.0 ? d / a : 0.0);
    opening.push_back(cs.point[net.point_begin[c]].un);
    broken.push_back(all_broken ? 1 : 0);
  }
  g.add_cell_data("damage", damage);
  g.add_cell_data("opening", opening);
  g.add_cell_data("broken", broken);
  g.add_cell_data("particle_a", particle_a);  // the particles' `id` in the particles series
  g.add_cell_data("particle_b", particle_b);
  g.add_cell_data("contact", contact);  // the contact's index (cells are in facet_order)
  emit(g, "facets", stamp, sim.time(), enc, facet_series_);
}

std::string History::join_columns(const std::vector<std::string>& columns) {
  std::string s;
  for (std::size_t i = 0; i < columns.size(); ++i) (s += i ? "," : "") += columns[i];
  return s;
}

History::History(const Simulation& sim, const Scenario& sc)
    : measures_(sim, sc), gauges_(sim.specimen()) {
  columns_ = {"step", "time_s"};
  for (const auto& p : sim.plates()) {
    columns_.push_back(p.name + "_displacement_m");
    columns_.push_back(p.name + "_force_N");
  }
  for (const auto& b : sim.pulled_bars()) {
    columns_.push_back(b.name + "_pull_displacement_m");
    columns_.push_back(b.name + "_pull_force_N");
  }
  for (const char* c :
       {"strain_x", "strain_y", "strain_z", "interior_strain_x", "interior_strain_y",
        "interior_strain_z", "load_N", "kinetic_J", "strain_J", "dissipated_damage_J",
        "dissipated_friction_J", "dissipated_damping_J", "external_work_J", "energy_balance_error",
        "damaged_points", "broken_points"})
    columns_.emplace_back(c);
  bars_ = !sim.nodes().empty();
  if (bars_)
    for (const char* c :
         {"max_axial_force_N", "yielded_nodes", "broken_interface_points", "dissipated_plastic_J"})
      columns_.emplace_back(c);
  adaptive_rate_ = sim.adaptive_loading_rate();
  if (adaptive_rate_) columns_.emplace_back("loading_rate_factor");
  for (const Gauge& g : measures_.gauges()) columns_.push_back("gauge_" + g.name() + "_m");
  for (const auto& p : sim.plates())
    if (p.motion.explicit_program()) columns_.push_back(p.name + "_program_segment");
  for (const auto& b : sim.pulled_bars())
    if (b.motion.explicit_program()) columns_.push_back(b.name + "_program_segment");
  if (measures_.several_plates()) columns_.emplace_back("control_displacement_m");
  for (std::size_t k = 0; k < sc.bars.size(); ++k)
    if (sc.bars[k].bent()) {
      bent_bars_.push_back(static_cast<int>(k));
      columns_.push_back(sc.bars[k].name + "_max_axial_force_N");
    }
  ties_ = sim.ties().size() > 0;
  if (ties_) columns_.emplace_back("max_tie_force_N");
  const auto plates = sc.load_plates();
  displacement_column_ = !sc.displacement_gauge.empty() ? "gauge_" + sc.displacement_gauge + "_m"
                         : plates.size() > 1            ? "control_displacement_m"
                         : plates.size() == 1           ? plates[0] + "_displacement_m"
                         : sc.control_bar.empty()       ? ""
                                                        : sc.control_bar + "_pull_displacement_m";
}

void History::record(const Simulation& sim) {
  std::vector<double> row = {static_cast<double>(sim.steps()), sim.time()};
  for (const auto& p : sim.plates()) {
    row.push_back(p.displacement);
    row.push_back(p.force[p.axis]);
  }
  for (const auto& b : sim.pulled_bars()) {
    row.push_back(b.displacement);
    row.push_back(b.load());
  }
  const Vec3 strain = gauges_.face(sim.bodies());
  const Vec3 interior = gauges_.interior(sim.bodies());
  row.insert(row.end(),
             {strain.x(), strain.y(), strain.z(), interior.x(), interior.y(), interior.z()});
  const Energy& e = sim.energy();
  row.insert(row.end(),
             {measures_.load(), e.kinetic, e.strain, e.damage, e.friction, e.damping,
              e.external_work, e.balance_error(), static_cast<double>(sim.damaged_points()),
              static_cast<double>(sim.broken_points())});
  if (bars_)
    row.insert(row.end(), {sim.max_axial_force(), static_cast<double>(sim.yielded_nodes()),
                           static_cast<double>(sim.broken_interface_points()), e.plastic});
  if (adaptive_rate_) row.push_back(sim.loading_rate_factor());
  for (const Gauge& g : measures_.gauges()) row.push_back(g.value(sim));
  for (const auto& p : sim.plates())
    if (p.motion.explicit_program()) row.push_back(static_cast<double>(p.motion.segment()));
  for (const auto& b : sim.pulled_bars())
    if (b.motion.explicit_program()) row.push_back(static_cast<double>(b.motion.segment()));
  if (measures_.several_plates()) row.push_back(measures_.control_displacement());
  if (!bent_bars_.empty()) {
    // The largest |N| over each bar's nodes, in one pass: a stirrup carries force where a crack
    // crosses it.
    std::vector<Real> most(sim.specimen().bars.size(), 0.0);
    for (std::size_t j = 0; j < sim.nodes().size(); ++j) {
      Real& m = most[static_cast<std::size_t>(sim.nodes()[j].bar)];
      m = std::max(m, std::abs(sim.node_states()[j].axial_force));
    }
    for (const int bar : bent_bars_) row.push_back(most[static_cast<std::size_t>(bar)]);
  }
  if (ties_) {
    Real most = 0.0;  // the largest force a tie carries, |N a_c + V|
    for (const NodeForces& f : sim.ties().forces()) most = std::max(most, f.force_a.norm());
    row.push_back(most);
  }
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
