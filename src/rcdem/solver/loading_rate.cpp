#include "rcdem/solver/loading_rate.hpp"

#include <algorithm>
#include <cmath>

namespace rcdem {

void LoadingRate::update(std::int64_t step, Real dt, const Energy& e) {
  if (!s_.adaptive || step % kCheckSteps != 0) return;
  // The strain energy from the ledger's balance (SPEC 11: W = E_s + E_k + D, kept within 1e-4).
  const Real strain = e.external_work - e.kinetic - e.dissipated();
  const Real work = e.external_work - st_.work, damage = e.damage - st_.damage;
  st_.work = e.external_work;
  st_.damage = e.damage;
  const bool burst = work > 0.0 ? damage > s_.damage_work_ratio * work : damage > 0.0;
  const Real ratio = strain > 0.0 ? e.kinetic / strain : HUGE_VAL;
  // Growth per check for about a doubling over doubling_time (a halving over a quarter of it):
  // 1 + ln 2 x, not 2^x, so that no libm function (whose last bit may differ between CPUs) enters
  // the loading.
  const Real interval = static_cast<Real>(kCheckSteps) * dt;
  const Real up = 1.0 + 0.6931471805599453 * interval / s_.doubling_time;
  if (burst || ratio > s_.kinetic_ratio)
    st_.factor = std::max(1.0, st_.factor / (up * up * up * up));
  else if (ratio < 0.5 * s_.kinetic_ratio)
    st_.factor = std::min(s_.max_factor, st_.factor * up);
}

}  // namespace rcdem
