// Diagnostic (not a benchmark): how the bodies' own stable time steps (SPEC 6, solver/
// body_stiffness.hpp) are spread over a scenario's specimen, and what selective mass scaling
// (solver.added_mass_limit, solver/selective_mass_scaling.hpp) would buy at each added-mass
// budget: the common step, its gain over the shortest estimate, how many bodies get heavier and
// by how much. The numbers behind docs/model.md 6's choice (bench/RESULTS.md, session 15).
// Usage: rcdem_mass_scaling_census SCENARIO.toml [LIMIT ...]   (default limits 0.001 ... 0.1)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/solver/selective_mass_scaling.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: rcdem_mass_scaling_census SCENARIO.toml [LIMIT ...]\n");
    return 1;
  }
  std::vector<double> limits;
  for (int i = 2; i < argc; ++i) {
    double v = -1;
    try {
      v = std::stod(argv[i]);
    } catch (const std::exception&) {
    }
    if (!(v >= 0.0)) {
      std::fprintf(stderr, "rcdem_mass_scaling_census: LIMIT '%s' must be a number >= 0\n",
                   argv[i]);
      return 1;
    }
    limits.push_back(v);
  }
  if (limits.empty()) limits = {0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1};
  rcdem::Progress::set_quiet_default(true);
  try {
    rcdem::Scenario sc = rcdem::load_scenario(argv[1]);
    sc.solver.added_mass_limit = 0.0;  // the bodies as SPEC 6 makes them
    const rcdem::Simulation sim(sc, rcdem::build_specimen(sc));
    const std::vector<rcdem::Real>& step = sim.mass_scaling().step;
    std::vector<rcdem::Real> sorted = step;
    std::sort(sorted.begin(), sorted.end());
    const auto at = [&](double q) {
      return sorted[std::min(sorted.size() - 1,
                             static_cast<std::size_t>(q * static_cast<double>(sorted.size())))];
    };
    std::printf("scenario=%s bodies=%zu shortest=%.4g s\n", argv[1], step.size(), sorted[0]);
    std::printf("# the bodies' own estimates: 0.1%% %.4g, 1%% %.4g, 10%% %.4g, median %.4g s\n",
                at(0.001), at(0.01), at(0.1), at(0.5));
    std::printf("# added_mass_limit  step_s  gain  bodies_scaled  largest_factor\n");
    for (const double limit : limits) {
      const rcdem::MassScalingPlan p =
          rcdem::plan_selective_mass_scaling(step, sim.bodies().mass, limit);
      std::printf("%g %.4g %.4f %lld %.3f\n", limit, p.time_step, p.time_step / p.unscaled_step,
                  static_cast<long long>(p.bodies_scaled), p.largest_factor);
    }
  } catch (const rcdem::Error& e) {
    std::fprintf(stderr, "rcdem_mass_scaling_census: %s\n", e.what());
    return 1;
  }
  return 0;
}
