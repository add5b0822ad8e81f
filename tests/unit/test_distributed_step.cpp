// The distributed step (issue 46, docs/parallel.md) without MPI: ranks as threads of this process
// exchanging through shared memory (ThreadRanks below implements core/communicator.hpp). A box
// pulled apart through its peak on 2, 3 and 5 such ranks ends with every body, point record,
// counter, crack log entry and ledger sum equal, bit for bit, to one simulation's; the
// decomposition's ranges cover every sphere and contact once, in whole blocks, and each rank
// evaluates every contact of its spheres.
#include <gtest/gtest.h>

#include <barrier>
#include <cstring>
#include <thread>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "rcdem/core/communicator.hpp"
#include "rcdem/solver/decomposition.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "small_scenarios.hpp"

using namespace rcdem;

namespace {

// What the ranks share: each call publishes its buffer, waits for all, reads the others', waits.
struct SharedRanks {
  explicit SharedRanks(int n) : size(n), sync(n), data(static_cast<std::size_t>(n)) {}
  int size;
  std::barrier<> sync;
  std::vector<void*> data;
};

class ThreadRanks final : public Communicator {
 public:
  ThreadRanks(SharedRanks& shared, int rank) : s_(&shared), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return s_->size; }

  void allgather(void* data, std::size_t bytes, const std::vector<Index>& offsets) override {
    publish(data);
    for (int r = 0; r < s_->size; ++r)
      if (r != rank_) copy_range(data, s_->data[static_cast<std::size_t>(r)], bytes, offsets, r);
    s_->sync.arrive_and_wait();
  }
  void gather(void* data, std::size_t bytes, const std::vector<Index>& offsets) override {
    publish(data);
    if (rank_ == 0)
      for (int r = 1; r < s_->size; ++r)
        copy_range(data, s_->data[static_cast<std::size_t>(r)], bytes, offsets, r);
    s_->sync.arrive_and_wait();
  }
  void broadcast(void* data, std::size_t bytes) override {
    publish(data);
    if (rank_ != 0) std::memcpy(data, s_->data[0], bytes);
    s_->sync.arrive_and_wait();
  }
  void gather_bytes(const std::vector<std::uint8_t>& local,
                    std::vector<std::uint8_t>& all) override {
    publish(const_cast<std::vector<std::uint8_t>*>(&local));
    all.clear();
    if (rank_ == 0)
      for (void* p : s_->data) {
        const auto& v = *static_cast<const std::vector<std::uint8_t>*>(p);
        all.insert(all.end(), v.begin(), v.end());
      }
    s_->sync.arrive_and_wait();
  }
  void all_to_all(const std::vector<std::uint8_t>& send, const std::vector<Index>& counts_out,
                  std::vector<std::uint8_t>& recv, const std::vector<Index>& counts_in) override {
    struct Out {
      const std::vector<std::uint8_t>* send;
      const std::vector<Index>* counts;
    } mine{&send, &counts_out};
    publish(&mine);
    const auto me = static_cast<std::size_t>(rank_);
    for (int r = 0; r < s_->size; ++r) {
      const auto& o = *static_cast<const Out*>(s_->data[static_cast<std::size_t>(r)]);
      const auto from = static_cast<std::size_t>((*o.counts)[me]);
      const auto n = static_cast<std::size_t>((*o.counts)[me + 1]) - from;
      const auto at = static_cast<std::size_t>(counts_in[static_cast<std::size_t>(r)]);
      if (n > 0) std::memcpy(recv.data() + at, o.send->data() + from, n);
    }
    s_->sync.arrive_and_wait();
  }
  void sum(std::int64_t* values, int count) override {
    std::vector<std::int64_t> mine(values, values + count);
    publish(mine.data());
    for (int k = 0; k < count; ++k) {
      values[k] = 0;
      for (void* p : s_->data) values[k] += static_cast<const std::int64_t*>(p)[k];
    }
    s_->sync.arrive_and_wait();
  }
  [[noreturn]] void abort(int) override { std::abort(); }

 private:
  void publish(void* data) {
    s_->data[static_cast<std::size_t>(rank_)] = data;
    s_->sync.arrive_and_wait();
  }
  static void copy_range(void* to, const void* from, std::size_t bytes,
                         const std::vector<Index>& offsets, int r) {
    const auto k = static_cast<std::size_t>(r);
    const auto at = static_cast<std::size_t>(offsets[k]) * bytes;
    const auto n = static_cast<std::size_t>(offsets[k + 1] - offsets[k]) * bytes;
    if (n > 0) std::memcpy(static_cast<char*>(to) + at, static_cast<const char*>(from) + at, n);
  }
  SharedRanks* s_;
  int rank_;
};

constexpr std::int64_t kSteps = 2500;  // through the box's peak: points damaged and broken

Scenario box() { return test::pulled_box("BL", "", 0.1); }

// What the comparison reads of a simulation after its steps.
struct Outcome {
  Bodies bodies;
  std::vector<LocalPointRecord> records;
  Index damaged = 0, broken = 0;
  std::vector<Index> log;
  Energy energy;
};

Outcome outcome(const Simulation& sim) {
  Outcome o;
  o.energy = sim.energy();
  o.bodies = sim.bodies();                  // distributed: gathers the spheres' motion onto rank 0
  const ContactState& cs = sim.contacts();  // ... and the whole state
  o.bodies.force = sim.bodies().force;
  o.records.assign(cs.point.records.begin(), cs.point.records.end());
  o.damaged = sim.damaged_points();
  o.broken = sim.broken_points();
  o.log = sim.broken_contact_log();
  return o;
}

Outcome distributed(int ranks) {
  SharedRanks shared(ranks);
  Outcome out;
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
#if defined(_OPENMP)
      omp_set_num_threads(1);
#endif
      ThreadRanks comm(shared, r);
      const Scenario sc = box();
      Simulation sim(sc, build_specimen(sc));
      sim.distribute(comm);
      if (r != 0) {
        (void)sim.follow();
        return;
      }
      sim.keep_strain_energy_every(100);
      for (std::int64_t k = 0; k < kSteps; ++k) {
        sim.step();
        // As a history row's gauges read them between steps: the gathered motion changes nothing.
        if (k % 500 == 0) EXPECT_TRUE(sim.bodies().position.back().allFinite());
      }
      out = outcome(sim);
      sim.tell_ranks(RankCommand::Finish);
    });
  for (auto& t : threads) t.join();
  return out;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

TEST(DistributedStep, SameBitsAsOneSimulationOnTwoThreeAndFiveRanks) {
  const Scenario sc = box();
  Simulation serial(sc, build_specimen(sc));
  serial.keep_strain_energy_every(100);
  for (std::int64_t k = 0; k < kSteps; ++k) serial.step();
  const Outcome one = outcome(serial);
  ASSERT_GT(one.broken, 0) << "the box must crack within the steps";
  for (const int ranks : {2, 3, 5}) {
    const Outcome d = distributed(ranks);
    EXPECT_TRUE(same_bytes(one.bodies.position, d.bodies.position)) << ranks << " ranks";
    EXPECT_TRUE(same_bytes(one.bodies.velocity, d.bodies.velocity)) << ranks << " ranks";
    EXPECT_TRUE(same_bytes(one.bodies.orientation, d.bodies.orientation)) << ranks << " ranks";
    EXPECT_TRUE(same_bytes(one.bodies.force, d.bodies.force)) << ranks << " ranks";
    EXPECT_TRUE(same_bytes(one.records, d.records)) << ranks << " ranks";
    EXPECT_EQ(one.damaged, d.damaged) << ranks << " ranks";
    EXPECT_EQ(one.broken, d.broken) << ranks << " ranks";
    EXPECT_EQ(one.log, d.log) << ranks << " ranks";
    EXPECT_EQ(std::memcmp(&one.energy, &d.energy, sizeof(Energy)), 0) << ranks << " ranks";
  }
}

TEST(Decomposition, RanksBeyondTheBlocksOwnAndEvaluateNothing) {
  // The box on DistributedStep's 5 ranks: more ranks than blocks of particles, so some own empty
  // ranges of particles and contacts, and evaluate no block.
  const Scenario sc = box();
  const Specimen sp = build_specimen(sc);
  int idle = 0;
  for (int r = 0; r < 5; ++r) {
    const Decomposition d = Decomposition::build(sp.contacts, sp.concrete(), r, 5);
    const auto k = static_cast<std::size_t>(r);
    if (d.sphere_offsets[k] != d.sphere_offsets[k + 1] ||
        d.contact_offsets[k] != d.contact_offsets[k + 1])
      continue;
    ++idle;
    EXPECT_TRUE(d.evaluated_blocks.empty()) << "rank " << r;
  }
  EXPECT_GT(idle, 0);
}

TEST(Decomposition, RangesCoverEverythingOnceInWholeBlocks) {
  const Scenario sc = test::small_box();
  const Specimen sp = build_specimen(sc);
  const ContactNetwork& net = sp.contacts;
  const Index spheres = sp.concrete();
  for (const int ranks : {1, 2, 3, 7}) {
    std::vector<int> evaluated(static_cast<std::size_t>(net.contact_count()), 0);
    for (int r = 0; r < ranks; ++r) {
      const Decomposition d = Decomposition::build(net, spheres, r, ranks);
      ASSERT_EQ(d.sphere_offsets.front(), 0);
      ASSERT_EQ(d.sphere_offsets.back(), spheres);
      ASSERT_EQ(d.contact_offsets.front(), 0);
      ASSERT_EQ(d.contact_offsets.back(), net.contact_count());
      for (int k = 1; k < ranks; ++k) {
        const auto i = static_cast<std::size_t>(k);
        EXPECT_LE(d.sphere_offsets[i - 1], d.sphere_offsets[i]);
        EXPECT_LE(d.contact_offsets[i - 1], d.contact_offsets[i]);
        EXPECT_TRUE(d.sphere_offsets[i] % Decomposition::kSphereBlock == 0 ||
                    d.sphere_offsets[i] == spheres);
        EXPECT_TRUE(d.contact_offsets[i] % Decomposition::kEnergyBlock == 0 ||
                    d.contact_offsets[i] == net.contact_count());
      }
      for (const Index b : d.evaluated_blocks)
        for (Index c = b * Decomposition::kContactBlock;
             c < std::min(net.contact_count(), (b + 1) * Decomposition::kContactBlock); ++c)
          evaluated[static_cast<std::size_t>(c)] = 1;
      const auto own = static_cast<std::size_t>(r);
      for (Index c = 0; c < net.contact_count(); ++c) {
        const bool mine = (net.particle_a[c] >= d.sphere_offsets[own] &&
                           net.particle_a[c] < d.sphere_offsets[own + 1]) ||
                          (net.particle_b[c] >= d.sphere_offsets[own] &&
                           net.particle_b[c] < d.sphere_offsets[own + 1]) ||
                          (c >= d.contact_offsets[own] && c < d.contact_offsets[own + 1]);
        if (mine) EXPECT_TRUE(evaluated[static_cast<std::size_t>(c)]) << "contact " << c;
      }
      std::fill(evaluated.begin(), evaluated.end(), 0);
    }
  }
}
