#include "rcdem/solver/rank_exchange.hpp"

#include <chrono>
#include <cstring>
#include <utility>

namespace rcdem {

// Adds the wall time of its scope to the exchange's.
class ExchangeTimer {
 public:
  explicit ExchangeTimer(const RankExchange& x) : x_(x), start_(std::chrono::steady_clock::now()) {}
  ~ExchangeTimer() {
    x_.seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ExchangeTimer(const ExchangeTimer&) = delete;
  ExchangeTimer& operator=(const ExchangeTimer&) = delete;

 private:
  const RankExchange& x_;
  std::chrono::steady_clock::time_point start_;
};

RankExchange::RankExchange(Communicator& comm, Decomposition d)
    : comm_(&comm),
      d_(std::move(d)),
      contact_blocks_(d_.contact_blocks(Decomposition::kContactBlock)),
      sphere_blocks_(d_.sphere_blocks(BodyStepSums::kSphereBlock)) {}

RankMessage RankExchange::exchange(RankMessage m) const {
  const ExchangeTimer timer(*this);
  comm_->broadcast(m);
  return m;
}

void RankExchange::share_dissipation(ContactState& cs) const {
  const ExchangeTimer timer(*this);
  if (!cs.block_damage.empty()) {
    comm_->allgather(cs.block_damage, contact_blocks_);
    comm_->allgather(cs.block_friction, contact_blocks_);
    return;
  }
  comm_->allgather(cs.dissipated_damage, d_.contact_offsets);
  comm_->allgather(cs.dissipated_friction, d_.contact_offsets);
}

void RankExchange::share_spheres(Bodies& b, BodyStepSums& sums) const {
  const ExchangeTimer timer(*this);
  const std::vector<Index>& spheres = d_.sphere_offsets;
  comm_->allgather(b.position, spheres);
  comm_->allgather(b.velocity, spheres);
  comm_->allgather(b.angular_velocity, spheres);
  comm_->allgather(b.orientation, spheres);
  comm_->allgather(b.angular_momentum, spheres);
  comm_->allgather(sums.blocks, sphere_blocks_);
}

void RankExchange::share_jumps(BodyStepSums& sums) const {
  comm_->allgather(sums.jumped, d_.sphere_offsets);
}

namespace {

template <class T>
void append(std::vector<std::uint8_t>& out, const T* data, std::size_t count) {
  const std::size_t at = out.size(), bytes = count * sizeof(T);
  out.resize(at + bytes);
  if (bytes > 0) std::memcpy(out.data() + at, data, bytes);
}

template <class T>
T take(const std::uint8_t*& p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  p += sizeof(T);
  return v;
}

}  // namespace

void RankExchange::gather_transitions(ContactState& cs, const ContactNetwork& net,
                                      const TallyMark& before) const {
  const ExchangeTimer timer(*this);
  // Each rank's message: its counters' changes, its new log entries, their points' records.
  std::vector<std::uint8_t>& mine = mine_;
  mine.clear();
  const std::int64_t head[3] = {
      cs.damaged_or_broken - before.damaged_or_broken, cs.broken - before.broken,
      static_cast<std::int64_t>(cs.broken_contact_log.size() - before.log)};
  append(mine, head, 3);
  if (!leader())
    for (std::size_t k = before.log; k < cs.broken_contact_log.size(); ++k) {
      const Index c = cs.broken_contact_log[k];
      append(mine, &c, 1);
      append(mine, cs.point.records.data() + net.point_begin[c],
             static_cast<std::size_t>(net.points_of(c)));
    }
  comm_->gather_bytes(mine, all_);
  const std::vector<std::uint8_t>& all = all_;
  if (!leader()) {
    cs.broken_contact_log.clear();  // rank 0 keeps the run's log
    return;
  }
  // Rank 0's own part first: the ranks own ascending ranges of contacts, so rank order is
  // contact order.
  const std::uint8_t* p = all.data() + sizeof(head);
  for (int r = 1; r < comm_->size(); ++r) {
    const auto damaged = take<std::int64_t>(p), broken = take<std::int64_t>(p);
    const auto entries = take<std::int64_t>(p);
    cs.damaged_or_broken += damaged;
    cs.broken += broken;
    for (std::int64_t k = 0; k < entries; ++k) {
      const auto c = take<Index>(p);
      cs.broken_contact_log.push_back(c);
      const auto n = static_cast<std::size_t>(net.points_of(c));
      std::memcpy(cs.point.records.data() + net.point_begin[c], p, n * sizeof(LocalPointRecord));
      p += n * sizeof(LocalPointRecord);
    }
  }
}

void RankExchange::gather_state(ContactState& cs, const ContactNetwork& net, Bodies& b,
                                BodyStepSums& sums) const {
  const ExchangeTimer timer(*this);
  const std::vector<Index>& contacts = d_.contact_offsets;
  comm_->gather(cs.normal, contacts);
  comm_->gather(cs.tangent, contacts);
  comm_->gather(cs.force_b, contacts);
  comm_->gather(cs.torque_b, contacts);
  comm_->gather(cs.torque_a, contacts);
  comm_->gather(cs.dissipated_damage, contacts);
  comm_->gather(cs.dissipated_friction, contacts);
  std::vector<Index> points(contacts.size());
  for (std::size_t r = 0; r < contacts.size(); ++r) points[r] = net.point_begin[contacts[r]];
  comm_->gather(cs.point.records, points);
  const std::vector<Index>& spheres = d_.sphere_offsets;
  comm_->gather(b.force, spheres);
  comm_->gather(b.torque, spheres);
  comm_->gather(sums.damping_work, spheres);
  comm_->gather(sums.kinetic, spheres);
  comm_->gather(sums.jumped, spheres);
}

}  // namespace rcdem
