#pragma once
// The local points' histories, each point in one record of two cache lines with a copy of what the
// contact loop reads of its network (position at t = 0, stiffness and strength): a contact's
// points are then one contiguous run of lines, so a visit fetches 2 lines per point, where nine
// history arrays and two network arrays took about 17 partly used lines for a contact of 6 points.
// The damaged contacts of a cracked beam lie scattered among condensed ones, so that fetch, not
// arithmetic, is the point path's largest cost (bench/RESULTS.md has the measurements).
#include <cstddef>
#include <vector>

#include "rcdem/contact/laws/local_point_state.hpp"
#include "rcdem/state/body_poses.hpp"  // AlignedAllocator
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// Line 1: what the step only reads, and the damage, stored only when it grows (the line then
// stays clean in most visits and is not written back). Line 2: the history every visit writes.
// Shear vectors are their components along the contact frame's axes (t1, t2).
struct alignas(64) LocalPointRecord {
  Real x0, y0, z0;                  // the point at t = 0 (ContactNetwork::point_position0)
  LocalPointConstants constants;    // (3)-(6) (ContactNetwork::constants)
  Real damage;                      // D (S4)
  Real fn, fs1, fs2, un, us1, us2;  // forces and accumulated displacements (SPEC 4-5)
  Real un_max, us_max_sq;           // the maxima that drive D (S3)

  [[gnu::always_inline]] PlanePointState state() const {
    PlanePointState s;
    s.fn = fn;
    s.fs = {fs1, fs2};
    s.un = un;
    s.us = {us1, us2};
    s.un_max = un_max;
    s.us_max_sq = us_max_sq;
    s.damage = damage;
    return s;
  }
  [[gnu::always_inline]] void store(const PlanePointState& s) {
    fn = s.fn;
    fs1 = s.fs.x;
    fs2 = s.fs.y;
    un = s.un;
    us1 = s.us.x;
    us2 = s.us.y;
    un_max = s.un_max;
    us_max_sq = s.us_max_sq;
    if (s.damage != damage) damage = s.damage;  // D only grows: rarely a write
  }
};
static_assert(sizeof(LocalPointRecord) == 128, "a record is two cache lines");

// A point's history as checkpoint columns (core/archive.hpp), in this order; its position and
// constants come with the regenerated specimen.
template <class Record, class R>
requires std::same_as<std::remove_const_t<R>, LocalPointRecord>
void archive_fields(Record& r, R& p) {
  r.put(p.fn);
  r.put(p.fs1);
  r.put(p.fs2);
  r.put(p.un);
  r.put(p.us1);
  r.put(p.us2);
  r.put(p.un_max);
  r.put(p.us_max_sq);
  r.put(p.damage);
}

// The damage of every point, read in place (outputs, counters).
struct PointDamage {
  const LocalPointRecord* records;
  std::size_t count;
  std::size_t size() const { return count; }
  Real operator[](std::size_t m) const { return records[m].damage; }
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
    const PlanePointState p = records[static_cast<std::size_t>(m)].state();
    LocalPointState s;
    s.fn = p.fn;
    s.fs = Vec3(p.fs.x, p.fs.y, 0.0);
    s.un = p.un;
    s.us = Vec3(p.us.x, p.us.y, 0.0);
    s.un_max = p.un_max;
    s.us_max_sq = p.us_max_sq;
    s.damage = p.damage;
    return s;
  }

  // The nine history values of point m, in the checkpoint's order (archive_fields below), each
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
    void put(T& v) {
      f(v);
    }
  };
};

}  // namespace rcdem
