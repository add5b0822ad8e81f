#pragma once
// Where and when the concrete's local points broke (D reached 1): the first cracking location and
// the growth of the cracks (SPEC 10: "cracking starts at the bottom near midspan and rises toward
// the load"), read off one small file instead of a facet snapshot at every step.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"

namespace rcdem {
class Simulation;
}

namespace rcdem::io {

class CrackRecord {
 public:
  explicit CrackRecord(const Simulation& sim);

  // Appends the points that broke since the last call, stamped with the step and the control's
  // deflection and load: the resolution is the spacing of the calls (the history's). Visits only
  // the contacts the simulation's log names since the last call, in contact order; the first call
  // after construction or a restore visits every point (the log starts empty then).
  void update(const Simulation& sim, Real deflection, Real load);

  // broken_points.csv: x_m,y_m,z_m,area_m2,step,deflection_m,load_N, in the order they broke.
  void write(const std::filesystem::path& path) const;

  // The first points to break: step, deflection, load, count, their area-weighted centroid and
  // their positions (at most 50); null if none broke.
  nlohmann::json first_cracking() const;

  std::size_t size() const { return rows_.size(); }

  // The checkpoint's "cracks.broken" flags and "cracks" rows (core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& c) {
    ar.bytes("cracks.broken", c.broken_);
    ar.list("cracks", c.rows_, member("position", "m", &Row::position),
            member("area", "m^2", &Row::area), member("step", "-", &Row::step),
            member("deflection", "m", &Row::deflection), member("load", "N", &Row::load));
    if constexpr (Archive::loading)
      if (ar.applying()) c.log_read_ = kScanAll;
  }

 private:
  struct Row {
    Vec3 position;
    Real area;
    std::int64_t step;
    Real deflection, load;
  };
  void add(const Simulation& sim, std::size_t point, Real deflection, Real load);
  void scan_all(const Simulation& sim, Real deflection, Real load);

  static constexpr std::size_t kScanAll = static_cast<std::size_t>(-1);
  std::vector<std::uint8_t> broken_;
  std::vector<Row> rows_;
  std::size_t log_read_ = kScanAll;  // entries of the simulation's log already visited
};

}  // namespace rcdem::io
