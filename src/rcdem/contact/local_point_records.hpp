#pragma once
// The local points' histories, each point in one record of two cache lines with a copy of what the
// contact loop reads of its network (position at t = 0, stiffness and strength): a contact's
// points are then one contiguous run of lines, so a visit fetches 2 lines per point, where nine
// history arrays and two network arrays took about 17 partly used lines for a contact of 6 points.
// The damaged contacts of a cracked beam lie scattered among condensed ones, so that fetch, not
// arithmetic, is the point path's largest cost (bench/RESULTS.md has the measurements).
#include <cstddef>
#include <type_traits>
#include <vector>

#include "rcdem/contact/laws/law_registry.hpp"  // PointHistory
#include "rcdem/core/archive.hpp"
#include "rcdem/state/body_poses.hpp"  // AlignedAllocator
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// A point: what the step only reads (56 bytes), then the law's state, which it reads and writes.
// The state's first field shares the first line (BasicPointState keeps D there, written only when
// it grows, so that line stays clean in most visits and is not written back); the rest is the
// second line. The loop over a set's points is a template on its law and copies the state in and
// out (store_state), so a law's update sees only its own State.
template <class History>
struct alignas(64) BasicLocalPointRecord {
  Real x0, y0, z0;                // the point at t = 0 (ContactNetwork::point_position0)
  LocalPointConstants constants;  // (3)-(6) (ContactNetwork::constants)
  History history;                // the law's state (law_registry.hpp, PointHistory)
};
using LocalPointRecord = BasicLocalPointRecord<PointHistory<PlaneVec>>;
static_assert(sizeof(LocalPointRecord) == 128, "a record is two cache lines");

// A point's history as checkpoint columns (core/archive.hpp): its state's; its position and
// constants come with the regenerated specimen.
template <class Record, class R>
requires std::same_as<std::remove_const_t<R>, LocalPointRecord>
void archive_fields(Record& r, R& p) { r.put(named("history", "", p.history)); }

// The damage of every point, read in place (outputs, counters).
struct PointDamage {
  const LocalPointRecord* records;
  std::size_t count;
  std::size_t size() const { return count; }
  Real operator[](std::size_t m) const { return records[m].history.damage; }
};

struct LocalPointRecords {
  std::vector<LocalPointRecord, AlignedAllocator<LocalPointRecord, 64>> records;

  // One record per point of `net`, with its position and constants, and an empty history. The
  // network's points must not change afterwards (they are built once with the specimen).
  void init(const ContactNetwork& net);
  Index size() const { return static_cast<Index>(records.size()); }
  LocalPointRecord* data() { return records.data(); }
  const LocalPointRecord* data() const { return records.data(); }
  PointDamage damage() const { return {records.data(), records.size()}; }

  // Point m with its shear vectors as frame components (t1, t2, 0) (ContactState::to_world turns
  // them into world vectors).
  LocalPointState operator[](Index m) const {
    return in_frame_components(records[static_cast<std::size_t>(m)].history);
  }

  // The history values of point m, in the checkpoint's order (archive_fields above), each
  // passed to f by reference.
  template <typename F>
  void for_each_history(Index m, F&& f) {
    Each<F> r{f};
    archive_fields(r, records[static_cast<std::size_t>(m)]);
  }
  template <typename F>
  void for_each_history(Index m, F&& f) const {
    Each<F> r{f};
    archive_fields(r, records[static_cast<std::size_t>(m)]);
  }

 private:
  template <typename F>
  struct Each {
    F& f;
    template <typename T>
    void put(Named<T> n) {
      put(n.value);
    }
    template <typename T>
    void put(T& v) {
      if constexpr (std::is_arithmetic_v<std::remove_const_t<T>>)
        f(v);
      else
        archive_fields(*this, v);  // a struct of values: its own fields, in order
    }
  };
};

}  // namespace rcdem
