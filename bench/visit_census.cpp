// Diagnostic (not a benchmark): from a run's checkpoint, STEPS steps, then the concrete contacts
// that neither the condensation nor the held sums evaluate (the next step visits their points),
// by the kinds of their points: I inside the envelope (no damage, or damaged with room to its
// caps), S softening along the normal envelope at its largest opening, B broken and open (no
// force), C broken, closed and sticking (|fs| below mu_c (-fn): linear with kn, ks while it stays
// so), K broken and carrying otherwise (sliding), X the rest (at a cap, shear damage read). With the held flags: how many of each kind the holds could take (held_contacts.hpp
// holds I+B and S+B, the latter when the softening clock lets it).
// Usage: rcdem_visit_census SCENARIO.toml STEPS CHECKPOINT
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/solver/concrete_contacts.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace {

double g_mu = 0.5;  // the scenario's mu_c
char point_kind(const rcdem::LocalPointRecord& p) {
  const rcdem::PlanePointState& s = p.history;
  const rcdem::LocalPointConstants& k = p.constants;
  if (s.damage >= 1) {
    if (s.fn == 0 && s.fs.x == 0 && s.fs.y == 0) return 'B';
    const double cap = g_mu * -s.fn;
    return s.fn < 0 && s.fs.x * s.fs.x + s.fs.y * s.fs.y < cap * cap ? 'C' : 'K';
  }
  const bool shear_read = k.ks * k.ks * s.us_max_sq > k.c_max * k.c_max;
  if (s.damage > 0 && s.un == s.un_max && s.fn == (1 - s.damage) * k.fn_max && !shear_read)
    return 'S';
  const rcdem::Real to_cap_n = (1 - s.damage) * k.fn_max - s.fn;
  const rcdem::Real to_cap_s = (1 - s.damage) * k.c_max - std::sqrt(s.fs.x * s.fs.x + s.fs.y * s.fs.y);
  return to_cap_n > 0 && to_cap_s > 0 && !shear_read ? 'I' : 'X';
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: rcdem_visit_census SCENARIO.toml STEPS CHECKPOINT\n");
    return 1;
  }
  rcdem::Progress::set_quiet_default(true);
  const long steps = std::atol(argv[2]);
  const rcdem::Scenario sc = rcdem::load_scenario(argv[1]);
  g_mu = sc.contact.mu_c;
  rcdem::Simulation sim(sc, rcdem::build_specimen(sc));
  const auto header = rcdem::io::inspect_checkpoint(argv[3]);
  rcdem::io::restore_checkpoint(argv[3], rcdem::io::CheckpointParts{&sim}, header.scenario_hash);
  for (long s = 0; s < steps; ++s) sim.step();
  const rcdem::ConcreteContacts* concrete = nullptr;
  for (const rcdem::StepPart* part : sim.parts())
    if (const auto* c = dynamic_cast<const rcdem::ConcreteContacts*>(part)) concrete = c;
  const auto& cond = concrete->condensation();
  const auto& net = sim.specimen().contacts;
  const auto& points = concrete->state().point.records;
  std::map<std::string, long> kinds;
  long visited = 0, held = 0, condensed = 0, waiting = 0, points_visited = 0;
  for (rcdem::Index c = 0; c < net.contact_count(); ++c) {
    const auto i = static_cast<std::size_t>(c);
    if (cond.held.held[i]) { ++held; continue; }
    if (cond.condensed[i]) { ++condensed; continue; }
    ++visited;
    bool present[128] = {};
    for (rcdem::Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m, ++points_visited)
      present[static_cast<unsigned char>(point_kind(points[static_cast<std::size_t>(m)]))] = true;
    std::string key;
    for (const char k : std::string("ISBCKX")) if (present[static_cast<unsigned char>(k)]) key += k;
    ++kinds[key];
    if (cond.held.softening_clock[i] < 0) ++waiting;
  }
  std::printf("contacts %ld: condensed %ld, held %ld, visited %ld (%ld points), softening clock "
              "waiting %ld\n",
              static_cast<long>(net.contact_count()), condensed, held, visited, points_visited,
              waiting);
  for (const auto& [key, n] : kinds) std::printf("  %-6s %6ld  %5.1f%%\n", key.c_str(), n,
                                                 100.0 * static_cast<double>(n) / static_cast<double>(visited));
  return 0;
}
