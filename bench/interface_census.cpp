// Diagnostic (not a benchmark): how much bond a scenario's steel-concrete interface can carry, from
// its generated specimen alone. Per bar: the interface contacts, their total (merged facet) area
// against the bar's surface pi D L, and the sum of the points' cohesive strengths C_max (SPEC 5,
// (6)) as a nominal bond stress over that surface, beside the stress needed to take the bar to
// yield over a given anchorage length, f_y A / (pi D l_a). Friction adds mu_c times any radial
// compression to the cohesion and is left out. Used by docs/case-study.md ("Bond sweep").
// Usage: rcdem_interface_census ANCHORAGE_LENGTH_M SCENARIO.toml [SCENARIO.toml ...]
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/specimens/specimen.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: rcdem_interface_census ANCHORAGE_LENGTH_M SCENARIO.toml [SCENARIO.toml "
                 "...]\n");
    return 1;
  }
  double anchorage = 0.0;
  try {
    anchorage = std::stod(argv[1]);
  } catch (const std::exception&) {
  }
  if (!(anchorage > 0.0)) {
    std::fprintf(stderr, "rcdem_interface_census: ANCHORAGE_LENGTH_M must be a length > 0 [m]\n");
    return 1;
  }
  rcdem::Progress::set_quiet_default(true);
  try {
    for (int k = 2; k < argc; ++k) {
      const rcdem::Scenario sc = rcdem::load_scenario(argv[k]);
      const rcdem::Specimen sp = rcdem::build_specimen(sc);
      if (sp.interfaces.empty()) std::printf("%s: no bars\n", argv[k]);
      for (const rcdem::InterfaceContacts& ic : sp.interfaces) {
        const rcdem::BarSettings& bar = sc.bars[static_cast<std::size_t>(ic.bar)];
        const double length = (bar.end - bar.start).norm();
        const double surface = std::numbers::pi * bar.diameter * length;
        double area = 0.0, cohesion = 0.0, tension = 0.0;
        for (double a : ic.net.facet_area) area += a;
        for (const auto& c : ic.net.constants) {
          cohesion += c.c_max;
          tension += c.fn_max;
        }
        const double yield = bar.f_y * std::numbers::pi * bar.diameter * bar.diameter / 4.0;
        const double bond = cohesion / surface;
        const double demand = yield / (std::numbers::pi * bar.diameter * anchorage);
        std::printf(
            "%s bar=%s D=%g contacts=%ld area_over_bar_surface=%.3f nominal_bond_strength_Pa=%.4g "
            "nominal_tensile_Pa=%.4g yield_bond_demand_Pa=%.4g anchorage_m=%g "
            "capacity_over_demand=%.3f\n",
            argv[k], bar.name.c_str(), bar.diameter, static_cast<long>(ic.net.contact_count()),
            area / surface, bond, tension / surface, demand, anchorage, bond / demand);
      }
    }
  } catch (const rcdem::Error& e) {
    std::fprintf(stderr, "rcdem: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
