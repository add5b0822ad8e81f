#include "rcdem/run/crack_record.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "rcdem/io/atomic_file.hpp"
#include "rcdem/solver/simulation.hpp"

namespace rcdem::io {

CrackRecord::CrackRecord(const Simulation& sim)
    : broken_(sim.point_damage().size(), std::uint8_t{0}) {}

void CrackRecord::update(const Simulation& sim, Real deflection, Real load) {
  const std::vector<Index>& log = sim.broken_contact_log();
  if (log_read_ == kScanAll || log_read_ > log.size()) {
    scan_all(sim, deflection, load);
    log_read_ = log.size();
    return;
  }
  if (log_read_ == log.size()) return;
  // In contact order, so in point order: the rows a scan of every point would append.
  std::vector<Index> contacts(log.begin() + static_cast<std::ptrdiff_t>(log_read_), log.end());
  log_read_ = log.size();
  std::sort(contacts.begin(), contacts.end());
  contacts.erase(std::unique(contacts.begin(), contacts.end()), contacts.end());
  const ContactNetwork& net = sim.specimen().contacts;
  for (const Index c : contacts)
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m)
      add(sim, static_cast<std::size_t>(m), deflection, load);
}

void CrackRecord::scan_all(const Simulation& sim, Real deflection, Real load) {
  for (std::size_t m = 0; m < broken_.size(); ++m) add(sim, m, deflection, load);
}

void CrackRecord::add(const Simulation& sim, std::size_t m, Real deflection, Real load) {
  if (broken_[m] || sim.point_damage()[m] < 1.0) return;
  broken_[m] = 1;
  const ContactNetwork& net = sim.specimen().contacts;
  const auto i = static_cast<Index>(m);
  rows_.push_back({net.point_position0[i], net.point_area[i], sim.steps(), deflection, load});
}

void CrackRecord::write(const std::filesystem::path& path) const {
  std::string out = "x_m,y_m,z_m,area_m2,step,deflection_m,load_N\n";
  for (const auto& r : rows_)
    out += fmt::format("{:.6g},{:.6g},{:.6g},{:.6g},{},{:.8g},{:.8g}\n", r.position.x(),
                       r.position.y(), r.position.z(), r.area, r.step, r.deflection, r.load);
  write_file_atomically(path, out);
}

nlohmann::json CrackRecord::first_cracking() const {
  if (rows_.empty()) return nullptr;
  const std::int64_t step = rows_.front().step;
  Vec3 centroid = Vec3::Zero();
  Real area = 0.0;
  nlohmann::json positions = nlohmann::json::array();
  std::size_t count = 0;
  for (const auto& r : rows_) {
    if (r.step != step) break;
    ++count;
    centroid += r.area * r.position;
    area += r.area;
    if (positions.size() < 50)
      positions.push_back({r.position.x(), r.position.y(), r.position.z()});
  }
  centroid /= area;
  return {{"step", step},
          {"deflection_m", rows_.front().deflection},
          {"load_N", rows_.front().load},
          {"points", count},
          {"centroid_m", {centroid.x(), centroid.y(), centroid.z()}},
          {"positions_m", positions}};
}

}  // namespace rcdem::io
