#pragma once
// The energy ledger of SPEC 11: external work = strain + kinetic + dissipated (damage, friction,
// damping), checked at the end of every run.
#include <algorithm>
#include <cmath>

#include "rcdem/core/types.hpp"

namespace rcdem {

struct Energy {
  Real external_work = 0.0;
  Real strain = 0.0;
  Real kinetic = 0.0;
  Real damage = 0.0;    // dissipated by contact damage (cumulative)
  Real friction = 0.0;  // dissipated by friction at contacts and plates (cumulative)
  Real damping = 0.0;   // removed by local damping (cumulative)
  Real plastic = 0.0;   // dissipated by the bars' yielding (cumulative)

  Real dissipated() const { return damage + friction + damping + plastic; }
  bool finite() const {
    return std::isfinite(external_work) && std::isfinite(strain) && std::isfinite(kinetic) &&
           std::isfinite(dissipated());
  }
  Real stored_and_lost() const { return strain + kinetic + dissipated(); }
  // |W - (E_s + E_k + D)| relative to the larger of W and the right-hand side.
  Real balance_error() const {
    const Real scale = std::max(std::abs(external_work), std::abs(stored_and_lost()));
    return scale > 0.0 ? std::abs(external_work - stored_and_lost()) / scale : 0.0;
  }
};

}  // namespace rcdem
