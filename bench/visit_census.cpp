// Diagnostic (not a benchmark): from a run's checkpoint, STEPS steps, then the concrete contacts
// that neither the condensation nor the held sums evaluate (the next step visits their points),
// by the kinds of their points: I inside the envelope (undamaged, or damaged below its caps), S
// softening along the normal envelope (held_contacts.hpp's on_normal_envelope), B broken and open
// (its broken_and_open), C broken, closed and sticking (|fs| below mu_c (-fn): linear with kn, ks
// while it stays so), K broken and carrying otherwise (sliding), X the rest (at a cap, shear
// damage read). Also the visited contacts whose softening clock makes them wait, and the held
// contacts by the kinds of their points at their entry. The holds take I+B and S+B, and intact
// contacts the condensation's bound sends to their points (held_contacts.hpp). Over the STEPS
// steps, the holds' turnover: contacts held after a step and not before it (entered) and the
// reverse (released), intact and damaged apart (a contact released and held again within one
// step is not seen).
// With FOLLOW > 0, the contacts that mix I and S points are then followed for FOLLOW steps: how
// many steps each stays visited with every point of its kind at the start (I still I, S still S
// and opening further), what a hold of mixed contacts could at most keep (its bound refuses some
// of them sooner).
// Usage: rcdem_visit_census SCENARIO.toml STEPS CHECKPOINT [FOLLOW]
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/held_contacts.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/solver/concrete_contacts.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace {

char point_kind(const rcdem::LocalPointRecord& p, rcdem::Real mu_c) {
  const rcdem::PlanePointState& s = p.history;
  const rcdem::LocalPointConstants& k = p.constants;
  const rcdem::Real fs_sq = s.fs.squaredNorm();
  if (s.damage >= 1) {
    if (rcdem::broken_and_open(s)) return 'B';
    const rcdem::Real cap = mu_c * -s.fn;
    return s.fn < 0 && fs_sq < cap * cap ? 'C' : 'K';
  }
  if (rcdem::on_normal_envelope(p)) return 'S';
  const bool shear_read = k.ks * k.ks * s.us_max_sq > k.c_max * k.c_max;
  const rcdem::Real to_cap_n = (1 - s.damage) * k.fn_max - s.fn;
  const rcdem::Real to_cap_s = (1 - s.damage) * k.c_max - std::sqrt(fs_sq);
  return to_cap_n > 0 && to_cap_s > 0 && !shear_read ? 'I' : 'X';
}

// The kinds present among contact c's points, in the order ISBCKX (e.g. "IS").
std::string kinds_of(const rcdem::ContactNetwork& net, const rcdem::LocalPointRecord* points,
                     rcdem::Index c, rcdem::Real mu_c) {
  std::string present;
  for (rcdem::Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m)
    present += point_kind(points[static_cast<std::size_t>(m)], mu_c);
  std::string key;
  for (const char k : std::string("ISBCKX"))
    if (present.find(k) != std::string::npos) key += k;
  return key;
}

const rcdem::ConcreteContacts& concrete_part(const rcdem::Simulation& sim) {
  for (const rcdem::StepPart* part : sim.parts())
    if (const auto* c = dynamic_cast<const rcdem::ConcreteContacts*>(part)) return *c;
  throw rcdem::Error("the scenario has no concrete contacts");
}

// Whether the next step visits contact c's points: neither held nor condensed.
bool visited(const rcdem::ConcreteContacts& concrete, rcdem::Index c) {
  const auto& cond = concrete.condensation();
  const auto i = static_cast<std::size_t>(c);
  return !cond.held.held[i] && !cond.condensed[i];
}

void census(const rcdem::Simulation& sim, rcdem::Real mu_c) {
  const rcdem::ConcreteContacts& concrete = concrete_part(sim);
  const auto& cond = concrete.condensation();
  const auto& net = sim.specimen().contacts;
  const auto& points = concrete.state().point.records;
  std::map<std::string, long> kinds, held_kinds;
  long visits = 0, held = 0, condensed = 0, waiting = 0, points_visited = 0;
  for (rcdem::Index c = 0; c < net.contact_count(); ++c) {
    const auto i = static_cast<std::size_t>(c);
    held += cond.held.held[i];
    condensed += cond.condensed[i] && !cond.held.held[i];
    if (cond.held.held[i]) ++held_kinds[kinds_of(net, points.data(), c, mu_c)];
    if (!visited(concrete, c)) continue;
    ++visits;
    points_visited += net.points_of(c);
    ++kinds[kinds_of(net, points.data(), c, mu_c)];
    waiting += cond.held.softening_clock[i] < 0;
  }
  std::printf(
      "contacts %ld: condensed %ld, held %ld, visited %ld (%ld points), softening clock "
      "waiting %ld\n",
      static_cast<long>(net.contact_count()), condensed, held, visits, points_visited, waiting);
  for (const auto& [key, n] : kinds)
    std::printf("  %-6s %6ld  %5.1f%%\n", key.c_str(), n,
                100.0 * static_cast<double>(n) / static_cast<double>(visits));
  std::printf("held contacts by their points' kinds at their entry:\n");
  for (const auto& [key, n] : held_kinds)
    std::printf("  %-6s %6ld  %5.1f%%\n", key.c_str(), n,
                100.0 * static_cast<double>(n) / static_cast<double>(std::max(held, 1L)));
}

// A followed contact: its points' kinds and openings at the last step, and how long it has lasted.
struct Followed {
  rcdem::Index contact;
  std::string kinds;
  std::vector<rcdem::Real> un;
  long steps = 0;
  bool alive = true;
};

// Whether f's points are still of their kinds, each S point opened further; updates its openings.
bool still_mixed(Followed& f, const rcdem::LocalPointRecord* points, rcdem::Index begin,
                 rcdem::Real mu_c) {
  for (std::size_t j = 0; j < f.kinds.size(); ++j) {
    const rcdem::LocalPointRecord& p = points[begin + static_cast<rcdem::Index>(j)];
    if (point_kind(p, mu_c) != f.kinds[j]) return false;
    if (f.kinds[j] == 'S' && !(p.history.un > f.un[j])) return false;
    f.un[j] = p.history.un;
  }
  return true;
}

void follow_mixed(rcdem::Simulation& sim, rcdem::Real mu_c, long steps) {
  const rcdem::ConcreteContacts& concrete = concrete_part(sim);
  const auto& net = sim.specimen().contacts;
  const auto& points = concrete.state().point.records;
  std::vector<Followed> list;
  for (rcdem::Index c = 0; c < net.contact_count(); ++c) {
    if (!visited(concrete, c)) continue;
    Followed f{c, "", {}};
    for (rcdem::Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
      f.kinds += point_kind(points[static_cast<std::size_t>(m)], mu_c);
      f.un.push_back(points[static_cast<std::size_t>(m)].history.un);
    }
    const bool mixed = f.kinds.find('I') != std::string::npos &&
                       f.kinds.find('S') != std::string::npos &&
                       f.kinds.find_first_not_of("IS") == std::string::npos;
    if (mixed) list.push_back(f);
  }
  for (long s = 0; s < steps; ++s) {
    sim.step();
    for (Followed& f : list) {
      if (!f.alive) continue;
      f.alive = visited(concrete, f.contact) &&
                still_mixed(f, points.data(), net.point_begin[f.contact], mu_c);
      f.steps += f.alive;
    }
  }
  std::map<long, long> lasted;  // by the power of 2 at or below the steps lasted (0: none)
  for (const Followed& f : list) {
    long bin = 0;
    while (f.steps >= 2 * std::max(bin, 1L) && bin < steps) bin = std::max(bin, 1L) * 2;
    ++lasted[f.steps == 0 ? 0 : std::max(bin, 1L)];
  }
  std::printf("mixed I+S contacts followed %ld steps: %zu; steps each stayed so (from):\n", steps,
              list.size());
  for (const auto& [bin, n] : lasted)
    std::printf("  %5ld  %6ld  %5.1f%%\n", bin, n,
                100.0 * static_cast<double>(n) / static_cast<double>(list.size()));
}

// STEPS steps, printing the holds' turnover (the file's head).
void step_counting_holds(rcdem::Simulation& sim, long steps) {
  const auto& cond = concrete_part(sim).condensation();
  long entered[2] = {0, 0}, released[2] = {0, 0};  // [0] damaged, [1] intact
  for (long s = 0; s < steps; ++s) {
    const std::vector<std::uint8_t> before = cond.held.held;
    sim.step();
    for (std::size_t i = 0; i < before.size(); ++i) {
      const int intact = cond.intact[i] ? 1 : 0;
      entered[intact] += !before[i] && cond.held.held[i];
      released[intact] += before[i] && !cond.held.held[i];
    }
  }
  std::printf(
      "holds over %ld steps: intact entered %ld, released %ld; damaged entered %ld, "
      "released %ld\n",
      steps, entered[1], released[1], entered[0], released[0]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: rcdem_visit_census SCENARIO.toml STEPS CHECKPOINT [FOLLOW]\n");
    return 1;
  }
  long steps = -1, follow = 0;
  try {
    steps = std::stol(argv[2]);
    if (argc == 5) follow = std::stol(argv[4]);
  } catch (const std::exception&) {
    steps = -1;
  }
  if (steps < 0 || follow < 0) {
    std::fprintf(stderr, "rcdem_visit_census: STEPS and FOLLOW must be whole numbers >= 0\n");
    return 1;
  }
  rcdem::Progress::set_quiet_default(true);
  try {
    const rcdem::Scenario sc = rcdem::load_scenario(argv[1]);
    rcdem::Simulation sim(sc, rcdem::build_specimen(sc));
    const auto header = rcdem::io::inspect_checkpoint(argv[3]);
    rcdem::io::restore_checkpoint(argv[3], rcdem::io::CheckpointParts{&sim}, header.scenario_hash);
    step_counting_holds(sim, steps);
    census(sim, sc.contact.mu_c);
    if (follow > 0) follow_mixed(sim, sc.contact.mu_c, follow);
  } catch (const rcdem::Error& e) {
    std::fprintf(stderr, "rcdem_visit_census: %s\n", e.what());
    return 1;
  }
  return 0;
}
