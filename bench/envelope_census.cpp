// Diagnostic (not a benchmark): from a run's checkpoint, how many damaged concrete contacts have
// every local point inside its BL envelope over a step (no cap, no damage growth: the offsets and
// the damage unchanged), and how many stay inside over the whole run of steps.
// Usage: rcdem_envelope_census SCENARIO.toml STEPS CHECKPOINT
#include <cmath>
#include <cstdio>
#include <string>
#include <cstdint>
#include <cstring>
#include <vector>

#include "rcdem/core/progress.hpp"
#include "rcdem/io/checkpoint.hpp"
#include "rcdem/io/scenario.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

int main(int argc, char** argv) {
  if (argc < 4) return 1;
  rcdem::Progress::set_quiet_default(true);
  const rcdem::Scenario sc = rcdem::load_scenario(argv[1]);
  rcdem::Simulation sim(sc, rcdem::build_specimen(sc));
  const auto header = rcdem::io::inspect_checkpoint(argv[3]);
  rcdem::io::restore_checkpoint(argv[3], rcdem::io::CheckpointParts{&sim}, header.scenario_hash);
  const long steps = std::stol(argv[2]);
  const auto& net = sim.specimen().contacts;
  const rcdem::Index nc = net.contact_count();
  std::vector<int> inside_run(nc, 0), longest(nc, 0);
  long sum_entries = 0, sum_exits = 0, sum_damaged = 0, sum_inside = 0, sum_open = 0, sum_from_sums = 0, sum_points_inside = 0, sum_dpoints = 0;
  for (long k = 0; k < steps; ++k) {
    const rcdem::LocalPointArrays before = sim.contacts().point;
    const std::vector<std::uint8_t> active_before = sim.condensation().damaged_active;
    const std::vector<rcdem::DamagedSums> entry_before = sim.condensation().damaged;
    sim.step();
    for (std::size_t c = 0; c < active_before.size(); ++c) {
      const bool now = sim.condensation().damaged_active[c];
      // Left and entered again within the step: new entry values.
      const bool again = active_before[c] && now &&
                         std::memcmp(&entry_before[c], &sim.condensation().damaged[c],
                                     sizeof(rcdem::DamagedSums)) != 0;
      sum_entries += (!active_before[c] && now) || again;
      sum_exits += (active_before[c] && !now) || again;
    }
    const rcdem::LocalPointArrays& after = sim.contacts().point;
    long damaged = 0, inside = 0, open = 0;
    for (rcdem::Index c = 0; c < nc; ++c) {
      bool any_d = false, all_in = true, all_open = true;
      for (rcdem::Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
        if (before.damage[m] > 0) any_d = true;
        // Inside the envelope: the offsets and the damage unchanged (local_point_state.hpp).
        const bool el = after.pn[m] == before.pn[m] && after.ps1[m] == before.ps1[m] &&
                        after.ps2[m] == before.ps2[m] && after.damage[m] == before.damage[m];
        if (before.damage[m] > 0) {
          ++sum_dpoints;
          if (el) ++sum_points_inside;
        }
        if (!el) all_in = false;
        if (!(before.damage[m] == 1 && after.un[m] == after.pn[m])) all_open = false;
      }
      if (!any_d) continue;
      ++damaged;
      if (all_in) ++inside;
      if (all_open) ++open;
      inside_run[c] = all_in ? inside_run[c] + 1 : 0;
      longest[c] = std::max(longest[c], inside_run[c]);
    }
    sum_damaged += damaged;
    sum_inside += inside;
    sum_open += open;
    sum_from_sums += sim.damaged_condensed_contacts();
    if (k % 20 == 0)
      std::printf("step %ld damaged_contacts %ld all_points_inside %ld fully_open %ld "
                  "damaged_from_sums %ld\n",
                  k, damaged, inside, open, static_cast<long>(sim.damaged_condensed_contacts()));
  }
  long whole = 0;
  for (rcdem::Index c = 0; c < nc; ++c)
    if (longest[c] >= steps) ++whole;
  const auto mean = [steps](long v) { return static_cast<double>(v) / static_cast<double>(steps); };
  std::printf("per step: entries %.1f exits %.1f (a contact leaving and "
              "entering again within a step counts in both)\n",
              mean(sum_entries), mean(sum_exits));
  std::printf("mean damaged %.0f inside %.0f open %.0f from_sums %.0f; damaged points inside "
              "%.3f; contacts inside every step %ld\n",
              mean(sum_damaged), mean(sum_inside), mean(sum_open), mean(sum_from_sums),
              static_cast<double>(sum_points_inside) / static_cast<double>(sum_dpoints), whole);
}
