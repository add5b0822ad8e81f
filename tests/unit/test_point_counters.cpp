// What a history row reports, kept by the step (issue 43, item 2): the damaged and broken points
// counted from each point's transitions equal a count over every point after every step, with
// and without the condensation of intact contacts, for both softening laws, at 1 and 2 threads;
// the crack record visiting only the logged contacts appends a row per broken point, the same rows
// as one that visits every point, and after a restore it finds the points that broke before the
// checkpoint; the strain energy kept while evaluating equals, bitwise, the one summed afterwards.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "rcdem/config/scenario.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/run/crack_record.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "small_scenarios.hpp"

using namespace rcdem;
namespace fs = std::filesystem;

namespace {

Scenario pulled_box(const std::string& law, bool condense) {
  return test::pulled_box(law, condense ? "" : "condense_elastic_contacts = false");
}

struct Scan {
  Index damaged = 0, broken = 0;
};

Scan scan(const Simulation& sim) {
  Scan s;
  const PointDamage d = sim.point_damage();
  for (std::size_t m = 0; m < d.size(); ++m) {
    s.damaged += d[m] > 0.0 && d[m] < 1.0;
    s.broken += d[m] >= 1.0;
  }
  return s;
}

std::string text_of(const io::CrackRecord& r, const fs::path& file) {
  r.write(file);
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void set_threads(int n) {
#if defined(_OPENMP)
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

// Steps the box until it has cracked through (or `steps`), checking the counters after every
// step; returns the last counts.
Scan check_counters(const Scenario& sc, int threads, int steps) {
  set_threads(threads);
  Simulation sim(sc, build_specimen(sc));
  Real peak = 0;
  for (int k = 0; k < steps; ++k) {
    sim.step();
    const Scan s = scan(sim);
    EXPECT_EQ(sim.damaged_points(), s.damaged) << "step " << sim.steps();
    EXPECT_EQ(sim.broken_points(), s.broken) << "step " << sim.steps();
    if (sim.damaged_points() != s.damaged || sim.broken_points() != s.broken) break;
    const Real load = -sim.find_plate("top")->force.z();
    peak = std::max(peak, load);
    if (peak > 0 && load < 0.1 * peak) break;
  }
  set_threads(2);
  return {sim.damaged_points(), sim.broken_points()};
}

}  // namespace

TEST(PointCounters, KeptByTheStepEqualACountOverEveryPoint) {
  for (const bool condense : {true, false})
    for (const int threads : {1, 2}) {
      SCOPED_TRACE(testing::Message() << "BL, condense " << condense << ", threads "
                                      << threads);
      EXPECT_GT(check_counters(pulled_box("BL", condense), threads, 6000).broken, 100);
    }
  // Its damage tends to 1 without reaching it: damaged points, none broken.
  SCOPED_TRACE("exponential");
  EXPECT_GT(check_counters(pulled_box("exponential", true), 2, 6000).damaged, 100);
}

TEST(PointCounters, CrackRecordFromTheLogEqualsAScanOfEveryPoint) {
  const Scenario sc = pulled_box("BL", true);
  // The same run twice: `sim` keeps its log; `ref` is restored from its own checkpoint before
  // every update, which clears its log, so that its record visits every point.
  Simulation sim(sc, build_specimen(sc)), ref(sc, build_specimen(sc));
  io::CrackRecord logged(sim), scanning(ref);
  const fs::path dir =
      fs::temp_directory_path() / ("rcdem_crack_record_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (int k = 1; k <= 4000; ++k) {
    sim.step();
    ref.step();
    if (k % 7 != 0) continue;
    const Real load = -sim.find_plate("top")->force.z();
    logged.update(sim, sim.time(), load);
    const io::CheckpointParts parts{&ref, nullptr, nullptr, &scanning};
    io::restore_checkpoint(io::write_checkpoint(dir, parts, 0), parts, 0);
    ASSERT_TRUE(ref.broken_contact_log().empty());
    scanning.update(ref, ref.time(), load);
    ASSERT_EQ(logged.size(), static_cast<std::size_t>(sim.broken_points())) << "step " << k;
    ASSERT_EQ(scanning.size(), logged.size()) << "step " << k;
  }
  EXPECT_GT(logged.size(), 100u);
  EXPECT_EQ(text_of(logged, dir / "logged.csv"), text_of(scanning, dir / "scanning.csv"));
  fs::remove_all(dir);
}

// Simulation::keep_strain_energy_every: the contacts' energies kept by the evaluation (the
// condensed kernel's in SIMD lanes, the others' from their points) give the strain energy a pass
// over the contacts after the step gives, to the bit, through the elastic stage and the cracking.
TEST(PointCounters, StrainEnergyKeptByTheStepEqualsTheSumAfterIt) {
  for (const char* law : {"BL", "exponential"}) {
    SCOPED_TRACE(law);
    const Scenario sc = pulled_box(law, true);
    Simulation kept(sc, build_specimen(sc)), summed(sc, build_specimen(sc));
    kept.keep_strain_energy_every(3);
    Index checked = 0;
    for (int k = 1; k <= 3000; ++k) {
      kept.step();
      summed.step();
      if (k % 3 != 0 && k % 50 != 0) continue;  // kept at every third step, summed at others
      ASSERT_EQ(kept.strain_energy(), summed.strain_energy()) << "step " << k;
      ++checked;
    }
    EXPECT_GT(summed.strain_energy(), 0.0);
    EXPECT_GT(summed.damaged_points() + summed.broken_points(), 100) << "it must crack";
    EXPECT_EQ(checked, 1000 + 40);  // every third step, and the 40 of every 50th that are not
  }
}
