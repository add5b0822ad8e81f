#include "rcdem/run/run_warnings.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rcdem {

void set_expectation(const Scenario& sc, RunOutcome& o) {
  const std::vector<std::string> load_plates = sc.load_plates();
  for (const auto& p : sc.plates) {
    if (std::find(load_plates.begin(), load_plates.end(), p.name) == load_plates.end()) continue;
    const Vec3& size = sc.specimen.size;
    const auto [u, v] = face_axes(p.axis);
    const std::vector<Real> r = p.rectangle(size);  // its part on the face:
    const Real width_u = std::min(r[1], size[u]) - std::max(r[0], 0.0);
    const Real width_v = std::min(r[3], size[v]) - std::max(r[2], 0.0);
    o.expected_load += sc.contact.sigma_nt * width_u * width_v;
    o.loaded_travel =
        std::max(o.loaded_travel, 10.0 * sc.contact.sigma_nt / sc.contact.E_bar * size[p.axis]);
  }
  for (const auto& b : sc.bars) {
    if (b.name != sc.control_bar) continue;
    o.expected_load = b.f_y * kPi / 4.0 * b.diameter * b.diameter;
    o.loaded_travel = 10.0 * b.f_y / b.E * b.length();
  }
}

std::vector<std::string> suspicious_run_warnings(const RunOutcome& o) {
  std::vector<std::string> w;
  if (o.expected_load > 0.0 && o.control_travel >= o.loaded_travel &&
      !(std::abs(o.peak_load) >= kSmallLoadFraction * o.expected_load))
    w.push_back(fmt::format(
        "the load never rose above {:.3g} N, {:.2g}% of the {:.3g} N expected once the control "
        "has moved {:.3g} m (it moved {:.3g} m): does the control plate or bar load the "
        "specimen?",
        o.peak_load, 100.0 * std::abs(o.peak_load) / o.expected_load, o.expected_load,
        o.loaded_travel, o.control_travel));
  if (!(o.balance_error <= kLargeBalanceError))
    w.push_back(fmt::format(
        "the energy balance is off by {:.3g}% at the end (a sound run keeps it below 0.01%): the "
        "time step or the loading is too coarse for this run",
        100.0 * o.balance_error));
  return w;
}

}  // namespace rcdem
