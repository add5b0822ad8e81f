// Diagnostic (not a benchmark): from a run's checkpoint, how many damaged concrete contacts have
// every local point inside its BL envelope over a step (the law's result equals the elastic
// update with slopes kn, ks: no cap, no damage growth), how many have every point fully damaged
// and open, and how many stay inside over the whole run of steps. What such contacts could gain
// from being evaluated from sums: docs/model.md §12, bench/RESULTS.md session 10.
// Usage: rcdem_envelope_census SCENARIO.toml STEPS CHECKPOINT
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: rcdem_envelope_census SCENARIO.toml STEPS CHECKPOINT\n");
    return 1;
  }
  long steps = 0;
  try {
    steps = std::stol(argv[2]);
  } catch (const std::exception&) {
  }
  if (steps <= 0) {
    std::fprintf(stderr, "rcdem_envelope_census: STEPS must be a whole number > 0\n");
    return 1;
  }
  rcdem::Progress::set_quiet_default(true);
  try {
    const rcdem::Scenario sc = rcdem::load_scenario(argv[1]);
    rcdem::Simulation sim(sc, rcdem::build_specimen(sc));
    const auto header = rcdem::io::inspect_checkpoint(argv[3]);
    rcdem::io::restore_checkpoint(argv[3], rcdem::io::CheckpointParts{&sim}, header.scenario_hash);
    const auto& net = sim.specimen().contacts;
    const rcdem::Index nc = net.contact_count();
    std::vector<long> inside_run(static_cast<std::size_t>(nc), 0);
    long sum_damaged = 0, sum_inside = 0, sum_open = 0, sum_points_inside = 0, sum_points = 0;
    for (long k = 0; k < steps; ++k) {
      const std::vector<rcdem::LocalPointRecord> before(sim.contacts().point.records.begin(),
                                                        sim.contacts().point.records.end());
      sim.step();
      const auto& after = sim.contacts().point.records;
      long damaged = 0, inside = 0, open = 0;
      for (rcdem::Index c = 0; c < nc; ++c) {
        bool any_damaged = false, all_inside = true, all_open = true;
        for (rcdem::Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
          const auto& kc = net.constants[m];
          const auto i = static_cast<std::size_t>(m);
          const auto& b = before[i].history;
          const auto& a = after[i].history;
          // The elastic update from the stored history (bilinear_softening.hpp), to rounding.
          const double fn = b.fn + kc.kn * (a.un - b.un);
          const double f1 = b.fs.x - kc.ks * (a.us.x - b.us.x);
          const double f2 = b.fs.y - kc.ks * (a.us.y - b.us.y);
          const double tol = 1e-9 * kc.fn_max;
          const bool in = std::abs(a.fn - fn) <= tol && std::abs(a.fs.x - f1) <= tol &&
                          std::abs(a.fs.y - f2) <= tol && a.damage == b.damage;
          if (b.damage > 0) {
            any_damaged = true;
            ++sum_points;
            sum_points_inside += in;
          }
          all_inside &= in;
          all_open &= b.damage == 1 && a.fn == 0;
        }
        if (!any_damaged) continue;
        ++damaged;
        inside += all_inside;
        open += all_open;
        auto& run = inside_run[static_cast<std::size_t>(c)];
        run = all_inside && run == k ? k + 1 : run;  // inside at every step so far
      }
      sum_damaged += damaged;
      sum_inside += inside;
      sum_open += open;
      if (k % 20 == 0)
        std::printf(
            "step +%ld: damaged contacts %ld, every point inside %ld, every point open %ld\n", k,
            damaged, inside, open);
    }
    const long whole = std::count(inside_run.begin(), inside_run.end(), steps);
    const auto mean = [steps](long v) {
      return static_cast<double>(v) / static_cast<double>(steps);
    };
    std::printf(
        "mean per step: damaged contacts %.0f, every point inside %.0f, every point open %.0f; "
        "damaged points inside %.3f; contacts inside at every one of the %ld steps %ld\n",
        mean(sum_damaged), mean(sum_inside), mean(sum_open),
        static_cast<double>(sum_points_inside) / static_cast<double>(std::max(1L, sum_points)),
        steps, whole);
  } catch (const rcdem::Error& e) {
    std::fprintf(stderr, "rcdem_envelope_census: %s\n", e.what());
    return 1;
  }
  return 0;
}
