#pragma once
// What a run writes as it goes: VTU snapshots of particles and facets with a .pvd series each,
// and the history table (SPEC 11). Every file is replaced atomically.
#include <filesystem>
#include <string>
#include <vector>

#include "rcdem/core/archive.hpp"
#include "rcdem/io/strain_gauges.hpp"
#include "rcdem/io/vtu_writer.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/solver/test_measures.hpp"

namespace rcdem::io {

class SnapshotWriter {
 public:
  SnapshotWriter(std::filesystem::path dir, bool binary, bool facets);
  void write(const Simulation& sim);  // snapshots/particles_NNNNNN.vtu, facets_NNNNNN.vtu, *.pvd

  // The checkpoint's "snapshots.<kind>" series: each snapshot's time, and its file names as text
  // (core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& w) {
    using Entry = std::pair<double, std::string>;
    ar.series("snapshots.particles", w.particle_series_, member("time", "s", &Entry::first),
              &Entry::second);
    ar.series("snapshots.facets", w.facet_series_, member("time", "s", &Entry::first),
              &Entry::second);
    ar.series("snapshots.bars", w.bar_series_, member("time", "s", &Entry::first), &Entry::second);
  }

 private:
  std::filesystem::path dir_;
  bool binary_, facets_;
  void write_bars(const Simulation& sim, const std::string& stamp, VtuEncoding enc);
  void emit(const UnstructuredGrid& g, const std::string& kind, const std::string& stamp,
            double time, VtuEncoding enc, std::vector<std::pair<double, std::string>>& series);
  std::vector<std::pair<double, std::string>> particle_series_, facet_series_, bar_series_;
  std::vector<Index> facet_order_;  // io::facet_order of the (fixed) network, at the first write
};

class History {
 public:
  // The columns: each plate's and pulled bar's, the strain gauges', the load and the ledger's,
  // the bars' where there are bars, then the scenario's gauges (gauge_NAME_m) and, for a load over
  // several plates, their mean displacement (control_displacement_m).
  History(const Simulation& sim, const Scenario& sc);
  // The column holding the test's displacement (summary.json's displacement_column).
  const std::string& displacement_column() const { return displacement_column_; }
  void record(const Simulation& sim);
  void write(const std::filesystem::path& path) const;
  std::size_t rows() const { return rows_.size(); }
  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::vector<double>>& data() const { return rows_; }
  const StrainGauges& gauges() const { return gauges_; }

  // The checkpoint's "history.columns" (which must equal this run's) and "history" rows.
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& h) {
    ar.expect_text("history.columns", join_columns(h.columns_));
    ar.rows("history", h.rows_, h.columns_.size());
  }

 private:
  static std::string join_columns(const std::vector<std::string>& columns);
  TestMeasures measures_;
  std::string displacement_column_;
  StrainGauges gauges_;
  bool bars_ = false;
  bool adaptive_rate_ = false;  // a loading_rate_factor column
  std::vector<int> bent_bars_;  // the bent bars' indices: a NAME_max_axial_force_N column each
  bool ties_ = false;           // a max_tie_force_N column
  std::vector<std::string> columns_;
  std::vector<std::vector<double>> rows_;
};

// Per-particle damage for display: the area-weighted mean D over the particle's local points.
std::vector<Real> particle_damage(const Simulation& sim);

}  // namespace rcdem::io
