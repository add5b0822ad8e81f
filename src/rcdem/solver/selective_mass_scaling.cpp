#include "rcdem/solver/selective_mass_scaling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace rcdem {

MassScalingPlan plan_selective_mass_scaling(const std::vector<Real>& step,
                                            const std::vector<Real>& mass, Real added_mass_limit) {
  const std::size_t n = step.size();
  MassScalingPlan plan;
  plan.factor.assign(n, 1.0);
  plan.step = step;
  plan.total_mass = std::accumulate(mass.begin(), mass.end(), Real{0});
  plan.unscaled_step = std::numeric_limits<Real>::infinity();
  for (const Real s : step) plan.unscaled_step = std::min(plan.unscaled_step, s);
  plan.time_step = plan.unscaled_step;
  if (!(added_mass_limit > 0.0) || !std::isfinite(plan.unscaled_step)) return plan;

  // Bodies by their estimate, shortest first (ties by number: the plan is deterministic).
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return step[a] < step[b]; });
  // With the k shortest raised to T: added(T) = T^2 sum(m / dt^2) - sum(m), increasing in T.
  // The target lies in the first interval [dt_(k), dt_(k+1)] where added reaches the budget.
  const Real budget = added_mass_limit * plan.total_mass;
  Real s = 0.0, m = 0.0;
  for (std::size_t k = 0; k < n && std::isfinite(step[order[k]]); ++k) {
    const std::size_t i = order[k];
    s += mass[i] / (step[i] * step[i]);
    m += mass[i];
    const Real target = std::sqrt((budget + m) / s);
    const Real next = k + 1 < n ? step[order[k + 1]] : std::numeric_limits<Real>::infinity();
    plan.time_step = std::min(target, next);
    if (target <= next) break;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!(step[i] < plan.time_step)) continue;
    const Real r = plan.time_step / step[i];
    plan.factor[i] = r * r;
    plan.added_mass += mass[i] * (plan.factor[i] - 1.0);
    plan.largest_factor = std::max(plan.largest_factor, plan.factor[i]);
    ++plan.bodies_scaled;
  }
  return plan;
}

}  // namespace rcdem
