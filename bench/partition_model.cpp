// The measured model of running past one machine (docs/parallel.md): a specimen's bodies
// partitioned by METIS over the contact graph into P parts, for each P what one rank would own,
// compute and receive per step, and from that and a stated machine the projected time per step.
// Partitioning needs no processes, so P may be far beyond this machine's cores.
//
// The decomposition it models: each rank owns its bodies and computes every contact that touches
// one of them (a contact cut by the partition is computed by both ranks, so no forces travel
// back), and receives each step what the kernels read of its ghost bodies (the bodies of its
// contacts that it does not own): the pose line and the angular velocity, kGhostBytes.
//
// Usage: rcdem_partition_model SCENARIO.toml OUT.csv P1,P2,... [--seconds-per-point S]
//            [--latency A] [--bandwidth B] [--seed K]
//   S: one core's step time per local point [s] (default 1.24e-8: the AN4 beam intact on a
//      16-core machine at 16 threads, per core, docs/parallel.md; rcdem_step_bench measures it);
//   A: a message's latency [s] (default 2e-6); B: a link's bandwidth [bytes/s] (default 1e10).
#include <metis.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace {

using rcdem::Index;

// What a contact kernel reads of a body it does not own: the pose line (BodyPoses, 8 doubles)
// and the angular velocity (3 doubles).
constexpr double kGhostBytes = 8 * 8 + 3 * 8;
// A bar's node or tie is not cut unless METIS must: weighted as this many local points.
constexpr idx_t kBarEdgeWeight = 1000;

// One edge of the body graph: its two bodies, the local points it carries (its owner's work; none
// for a bar's node or tie) and its weight for METIS (a cut's cost).
struct Edge {
  Index a, b;
  idx_t points, weight;
};

std::vector<Edge> body_graph(const rcdem::Specimen& s, Index& bodies) {
  std::vector<Edge> edges;
  const auto add_network = [&](const rcdem::ContactNetwork& net) {
    for (Index c = 0; c < net.contact_count(); ++c) {
      const auto points = static_cast<idx_t>(net.points_of(c));
      edges.push_back({net.particle_a[c], net.particle_b[c], points, points});
    }
  };
  add_network(s.contacts);
  for (const auto& in : s.interfaces) add_network(in.net);
  // The cylinders are bodies after the concrete particles, bar by bar (specimen.hpp).
  std::vector<Index> first(s.bars.size() + 1, s.concrete());
  for (std::size_t k = 0; k < s.bars.size(); ++k)
    first[k + 1] = first[k] + static_cast<Index>(s.bars[k].cylinders.size());
  for (std::size_t k = 0; k < s.bars.size(); ++k)
    for (const auto& node : s.bars[k].nodes)
      edges.push_back({first[k] + node[0], first[k] + node[1], 0, kBarEdgeWeight});
  for (const auto& t : s.ties)
    edges.push_back({first[static_cast<std::size_t>(t.bar_a)] + t.cylinder_a,
                     first[static_cast<std::size_t>(t.bar_b)] + t.cylinder_b, 0, kBarEdgeWeight});
  bodies = first.back();
  return edges;
}

// METIS's graph: symmetric CSR without self-loops, parallel edges merged; a body's weight is the
// local points of its contacts (what its owner computes).
struct MetisGraph {
  std::vector<idx_t> xadj, adjncy, adjwgt, vwgt;
};

MetisGraph metis_graph(const std::vector<Edge>& edges, Index bodies) {
  std::vector<std::map<Index, idx_t>> adj(static_cast<std::size_t>(bodies));
  MetisGraph g;
  g.vwgt.assign(static_cast<std::size_t>(bodies), 1);
  for (const Edge& e : edges) {
    if (e.a == e.b) continue;
    adj[static_cast<std::size_t>(e.a)][e.b] += e.weight;
    adj[static_cast<std::size_t>(e.b)][e.a] += e.weight;
    g.vwgt[static_cast<std::size_t>(e.a)] += e.points;
    g.vwgt[static_cast<std::size_t>(e.b)] += e.points;
  }
  g.xadj.push_back(0);
  for (const auto& row : adj) {
    for (const auto& [j, w] : row) {
      g.adjncy.push_back(static_cast<idx_t>(j));
      g.adjwgt.push_back(w);
    }
    g.xadj.push_back(static_cast<idx_t>(g.adjncy.size()));
  }
  return g;
}

// What one partition asks of its ranks.
struct RankLoad {
  long owned = 0, ghosts = 0, neighbours = 0;
  long points = 0;  // local points of the contacts it computes (cut ones counted by both ranks)
};

std::vector<RankLoad> rank_loads(const std::vector<Edge>& edges, const std::vector<idx_t>& part,
                                 int parts) {
  std::vector<RankLoad> load(static_cast<std::size_t>(parts));
  std::vector<std::set<Index>> ghosts(static_cast<std::size_t>(parts));
  for (const idx_t p : part) ++load[static_cast<std::size_t>(p)].owned;
  for (const Edge& e : edges) {
    const auto pa = static_cast<std::size_t>(part[static_cast<std::size_t>(e.a)]);
    const auto pb = static_cast<std::size_t>(part[static_cast<std::size_t>(e.b)]);
    load[pa].points += e.points;
    if (pa == pb) continue;
    load[pb].points += e.points;
    ghosts[pa].insert(e.b);
    ghosts[pb].insert(e.a);
  }
  for (std::size_t r = 0; r < load.size(); ++r) {
    std::set<idx_t> from;
    for (const Index g : ghosts[r]) from.insert(part[static_cast<std::size_t>(g)]);
    load[r].ghosts = static_cast<long>(ghosts[r].size());
    load[r].neighbours = static_cast<long>(from.size());
  }
  return load;
}

struct Machine {
  double seconds_per_point = 1.24e-8, latency = 2e-6, bandwidth = 1e10;
};

std::vector<int> parse_parts(const std::string& text) {
  std::vector<int> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    const std::string item = text.substr(pos, comma - pos);
    char* end = nullptr;
    const long p = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || p < 1 || p > 1000000)
      rcdem::fail("P must be whole numbers from 1 to 1000000, got '{}'", text);
    out.push_back(static_cast<int>(p));
    pos = comma + 1;
  }
  return out;
}

// The options after the three positional arguments, each a name and a number > 0.
Machine machine_options(int argc, char** argv, idx_t& seed) {
  Machine m;
  double seed_value = 1;
  for (int i = 4; i < argc; i += 2) {
    const std::string name = argv[i];
    char* end = nullptr;
    const double v = std::strtod(argv[i + 1], &end);
    if (end == argv[i + 1] || *end != '\0' || !std::isfinite(v) || v <= 0)
      rcdem::fail("{} expects a number > 0, got '{}'", name, argv[i + 1]);
    if (name == "--seconds-per-point")
      m.seconds_per_point = v;
    else if (name == "--latency")
      m.latency = v;
    else if (name == "--bandwidth")
      m.bandwidth = v;
    else if (name == "--seed")
      seed_value = v;
    else
      rcdem::fail("unknown option '{}'", name);
  }
  seed = static_cast<idx_t>(seed_value);
  return m;
}

std::vector<idx_t> partition(MetisGraph& g, int parts, idx_t seed) {
  idx_t n = static_cast<idx_t>(g.vwgt.size()), ncon = 1, np = parts, cut = 0;
  std::vector<idx_t> part(static_cast<std::size_t>(n), 0);
  if (parts == 1) return part;
  idx_t opts[METIS_NOPTIONS];
  METIS_SetDefaultOptions(opts);
  opts[METIS_OPTION_SEED] = seed;
  const int rc =
      METIS_PartGraphKway(&n, &ncon, g.xadj.data(), g.adjncy.data(), g.vwgt.data(), nullptr,
                          g.adjwgt.data(), &np, nullptr, nullptr, opts, &cut, part.data());
  if (rc != METIS_OK) rcdem::fail("METIS failed for P = {}", parts);
  return part;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4 || argc % 2 == 1) {
    std::fprintf(stderr,
                 "usage: rcdem_partition_model SCENARIO.toml OUT.csv P1,P2,... "
                 "[--seconds-per-point S] [--latency A] [--bandwidth B] [--seed K]\n");
    return 1;
  }
  rcdem::Progress::set_quiet_default(true);
  try {
    const std::vector<int> all_parts = parse_parts(argv[3]);
    idx_t seed = 1;
    const Machine m = machine_options(argc, argv, seed);
    const rcdem::Specimen s = rcdem::build_specimen(rcdem::load_scenario(argv[1]));
    Index bodies = 0;
    const std::vector<Edge> edges = body_graph(s, bodies);
    MetisGraph g = metis_graph(edges, bodies);
    long total_points = 0;
    for (const Edge& e : edges) total_points += e.points;
    const double t1 = m.seconds_per_point * static_cast<double>(total_points);
    std::FILE* out = std::fopen(argv[2], "w");
    if (!out) rcdem::fail("cannot write {}", argv[2]);
    std::fprintf(out,
                 "P,bodies,local_points,max_points,mean_points,imbalance,duplicated_share,"
                 "max_ghosts,mean_ghosts,max_neighbours,max_bytes_per_step,t_compute_s,"
                 "t_exchange_s,t_allreduce_s,t_step_s,speedup,efficiency\n");
    for (const int p : all_parts) {
      const std::vector<RankLoad> load = rank_loads(edges, partition(g, p, seed), p);
      long max_pts = 0, sum_pts = 0, max_gh = 0, sum_gh = 0, max_nb = 0;
      for (const RankLoad& r : load) {
        max_pts = std::max(max_pts, r.points);
        sum_pts += r.points;
        max_gh = std::max(max_gh, r.ghosts);
        sum_gh += r.ghosts;
        max_nb = std::max(max_nb, r.neighbours);
      }
      const double mean_pts = static_cast<double>(sum_pts) / p;
      const double bytes = kGhostBytes * static_cast<double>(max_gh);
      const double t_comp = m.seconds_per_point * static_cast<double>(max_pts);
      // One message from each neighbour; the global sums (reactions, energies, the stop rule):
      // one allreduce, log2 P latencies up and down.
      const double t_x = p > 1 ? static_cast<double>(max_nb) * m.latency + bytes / m.bandwidth : 0;
      const double t_red = p > 1 ? 2 * std::ceil(std::log2(p)) * m.latency : 0;
      const double t = t_comp + t_x + t_red;
      std::fprintf(
          out, "%d,%ld,%ld,%ld,%.1f,%.4f,%.4f,%ld,%.1f,%ld,%.0f,%.4e,%.4e,%.4e,%.4e,%.3f,%.4f\n", p,
          static_cast<long>(bodies), total_points, max_pts, mean_pts,
          static_cast<double>(max_pts) / mean_pts,
          static_cast<double>(sum_pts - total_points) / static_cast<double>(total_points), max_gh,
          static_cast<double>(sum_gh) / p, max_nb, bytes, t_comp, t_x, t_red, t, t1 / t,
          t1 / t / p);
      std::fflush(out);
      std::printf("P=%d max_points=%ld ghosts=%ld neighbours=%ld t_step=%.3e speedup=%.1f\n", p,
                  max_pts, max_gh, max_nb, t, t1 / t);
    }
    std::fclose(out);
  } catch (const rcdem::Error& e) {
    std::fprintf(stderr, "rcdem_partition_model: %s\n", e.what());
    return 1;
  }
  return 0;
}
