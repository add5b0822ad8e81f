#include "rcdem/solver/rank_exchange.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <utility>

namespace rcdem {

// Adds the wall time of its scope to the exchange's.
class ExchangeTimer {
 public:
  ExchangeTimer(const RankExchange& x, ExchangeKind kind)
      : x_(x), kind_(static_cast<std::size_t>(kind)), start_(std::chrono::steady_clock::now()) {}
  ~ExchangeTimer() {
    x_.seconds_[kind_] +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ExchangeTimer(const ExchangeTimer&) = delete;
  ExchangeTimer& operator=(const ExchangeTimer&) = delete;

 private:
  const RankExchange& x_;
  std::size_t kind_;
  std::chrono::steady_clock::time_point start_;
};

namespace {

// A sphere's motion as a ghost receives it: position, velocity, spin, orientation, angular
// momentum (16 words).
constexpr std::size_t kGhostBytes = 3 * sizeof(Vec3) + sizeof(Quat) + sizeof(Vec3);
static_assert(sizeof(Vec3) == 24 && sizeof(Quat) == 32, "the ghost message's layout");

// The spheres rank d.rank reads and does not advance, ascending: the ends of the contacts it
// evaluates and the shared ones.
std::vector<Index> ghosts_of(const ContactNetwork& net, const Decomposition& d,
                             const std::vector<Index>& shared) {
  const Index spheres = d.sphere_offsets.back();
  const auto k = static_cast<std::size_t>(d.rank);
  const Index lo = d.sphere_offsets[k], hi = d.sphere_offsets[k + 1];
  std::vector<std::uint8_t> read(static_cast<std::size_t>(spheres), 0);
  for (const Index b : d.evaluated_blocks)
    for (Index c = b * Decomposition::kContactBlock;
         c < std::min(net.contact_count(), (b + 1) * Decomposition::kContactBlock); ++c) {
      read[static_cast<std::size_t>(net.particle_a[c])] = 1;
      read[static_cast<std::size_t>(net.particle_b[c])] = 1;
    }
  for (const Index i : shared)
    if (i < spheres) read[static_cast<std::size_t>(i)] = 1;
  std::vector<Index> out;
  for (Index i = 0; i < spheres; ++i)
    if (read[static_cast<std::size_t>(i)] && (i < lo || i >= hi)) out.push_back(i);
  return out;
}

// Offsets [0, c0, c0 + c1, ...] of `counts` items of `unit` bytes each.
std::vector<Index> byte_offsets(const std::vector<Index>& counts, std::size_t unit) {
  std::vector<Index> out(1, 0);
  for (const Index c : counts) out.push_back(out.back() + c * static_cast<Index>(unit));
  return out;
}

// Every rank sends rank k its `items` [sum of count_out[< k], + count_out[k]) and receives
// count_in[r] items from each rank r, in rank order.
std::vector<Index> swap_indices(Communicator& comm, const std::vector<Index>& items,
                                const std::vector<Index>& count_out,
                                const std::vector<Index>& count_in) {
  std::vector<std::uint8_t> out(items.size() * sizeof(Index));
  if (!out.empty()) std::memcpy(out.data(), items.data(), out.size());
  const std::vector<Index> to = byte_offsets(count_out, sizeof(Index));
  const std::vector<Index> from = byte_offsets(count_in, sizeof(Index));
  std::vector<std::uint8_t> in(static_cast<std::size_t>(from.back()));
  comm.all_to_all(out, to, in, from);
  std::vector<Index> got(in.size() / sizeof(Index));
  if (!in.empty()) std::memcpy(got.data(), in.data(), in.size());
  return got;
}

}  // namespace

RankExchange::RankExchange(Communicator& comm, Decomposition d, const ContactNetwork& net,
                           const std::vector<Index>& shared)
    : comm_(&comm),
      d_(std::move(d)),
      contact_blocks_(Decomposition::in_blocks(d_.contact_offsets, Decomposition::kContactBlock)),
      sphere_blocks_(Decomposition::in_blocks(d_.sphere_offsets, Decomposition::kSphereBlock)) {
  // Each rank lists its ghosts (ascending, so grouped by their owners) and sends each owner the
  // part it owns: what the owner then sends every step.
  receive_ = ghosts_of(net, d_, shared);
  std::vector<Index> asked(static_cast<std::size_t>(d_.ranks), 0);  // of each owner
  for (const Index i : receive_) {
    const auto next = std::upper_bound(d_.sphere_offsets.begin(), d_.sphere_offsets.end(), i);
    ++asked[static_cast<std::size_t>(next - d_.sphere_offsets.begin() - 1)];
  }
  const std::vector<Index> one(asked.size(), 1);
  const std::vector<Index> giving = swap_indices(*comm_, asked, one, one);  // to each rank
  send_ = swap_indices(*comm_, receive_, asked, giving);
  receive_bytes_ = byte_offsets(asked, kGhostBytes);
  send_bytes_ = byte_offsets(giving, kGhostBytes);
  out_.resize(send_.size() * kGhostBytes);
  in_.resize(receive_.size() * kGhostBytes);
}

RankMessage RankExchange::exchange(RankMessage m) const {
  const ExchangeTimer timer(*this, ExchangeKind::Command);
  comm_->broadcast(m);
  return m;
}

void RankExchange::share_dissipation(ContactState& cs) const {
  const ExchangeTimer timer(*this, ExchangeKind::Dissipation);
  if (!cs.block_damage.empty()) {
    comm_->allgather(cs.block_damage, contact_blocks_);
    comm_->allgather(cs.block_friction, contact_blocks_);
    return;
  }
  comm_->allgather(cs.dissipated_damage, d_.contact_offsets);
  comm_->allgather(cs.dissipated_friction, d_.contact_offsets);
}

void RankExchange::share_spheres(Bodies& b, BodyStepSums& sums) const {
  const ExchangeTimer timer(*this, ExchangeKind::Spheres);
  std::uint8_t* o = out_.data();
  for (const Index i : send_) {
    std::memcpy(o, b.position[i].data(), sizeof(Vec3));
    std::memcpy(o + 24, b.velocity[i].data(), sizeof(Vec3));
    std::memcpy(o + 48, b.angular_velocity[i].data(), sizeof(Vec3));
    std::memcpy(o + 72, b.orientation[i].coeffs().data(), sizeof(Quat));
    std::memcpy(o + 104, b.angular_momentum[i].data(), sizeof(Vec3));
    o += kGhostBytes;
  }
  comm_->all_to_all(out_, send_bytes_, in_, receive_bytes_);
  const std::uint8_t* p = in_.data();
  for (const Index i : receive_) {
    std::memcpy(b.position[i].data(), p, sizeof(Vec3));
    std::memcpy(b.velocity[i].data(), p + 24, sizeof(Vec3));
    std::memcpy(b.angular_velocity[i].data(), p + 48, sizeof(Vec3));
    std::memcpy(b.orientation[i].coeffs().data(), p + 72, sizeof(Quat));
    std::memcpy(b.angular_momentum[i].data(), p + 104, sizeof(Vec3));
    p += kGhostBytes;
  }
  comm_->allgather(sums.blocks, sphere_blocks_);
}

void RankExchange::share_jumps(BodyStepSums& sums) const {
  const ExchangeTimer timer(*this, ExchangeKind::Spheres);
  comm_->allgather(sums.jumped, d_.sphere_offsets);
}

std::vector<ExchangeSeconds> RankExchange::gather_seconds() const {
  std::vector<ExchangeSeconds> all(static_cast<std::size_t>(comm_->size()));
  all[static_cast<std::size_t>(comm_->rank())] = seconds_;
  std::vector<Index> one_each(all.size() + 1);
  for (std::size_t r = 0; r < one_each.size(); ++r) one_each[r] = static_cast<Index>(r);
  comm_->gather(all, one_each);
  return all;
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
  const ExchangeTimer timer(*this, ExchangeKind::CrackLog);
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

void RankExchange::gather_motion(Bodies& b) const {
  const ExchangeTimer timer(*this, ExchangeKind::Requests);
  const std::vector<Index>& spheres = d_.sphere_offsets;
  comm_->gather(b.position, spheres);
  comm_->gather(b.velocity, spheres);
  comm_->gather(b.angular_velocity, spheres);
  comm_->gather(b.orientation, spheres);
  comm_->gather(b.angular_momentum, spheres);
}

std::vector<Index> RankExchange::read_bodies(Index bodies) const {
  const auto r = static_cast<std::size_t>(d_.rank);
  std::vector<Index> out(receive_);
  for (Index i = d_.sphere_offsets[r]; i < d_.sphere_offsets[r + 1]; ++i) out.push_back(i);
  for (Index i = d_.sphere_offsets.back(); i < bodies; ++i) out.push_back(i);
  std::sort(out.begin(), out.end());
  return out;
}

void RankExchange::gather_state(ContactState& cs, const ContactNetwork& net, Bodies& b,
                                BodyStepSums& sums) const {
  gather_motion(b);
  const ExchangeTimer timer(*this, ExchangeKind::Requests);
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
