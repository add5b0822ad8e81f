#include "rcdem/run/checkpoint.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <map>
#include <type_traits>

#include "rcdem/core/build_info.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/run/crack_record.hpp"
#include "rcdem/run/run_output.hpp"
#include "rcdem/solver/simulation.hpp"

namespace rcdem::io {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Checksums.

namespace {

struct Crc32Tables {
  std::uint32_t t[8][256];
  constexpr Crc32Tables() : t{} {
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1U) ? 0xEDB88320U ^ (c >> 1) : c >> 1;
      t[0][i] = c;
    }
    for (std::uint32_t i = 0; i < 256; ++i)
      for (int s = 1; s < 8; ++s) t[s][i] = (t[s - 1][i] >> 8) ^ t[0][t[s - 1][i] & 0xFFU];
  }
};
constexpr Crc32Tables kCrc{};

std::uint32_t load_le32(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}
std::uint64_t load_le64(const unsigned char* p) {
  return static_cast<std::uint64_t>(load_le32(p)) | static_cast<std::uint64_t>(load_le32(p + 4))
                                                        << 32;
}

}  // namespace

std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc) {
  // Slicing by 8: eight table look-ups per 8 bytes (a few GB/s), the same result as bytewise.
  const auto* p = static_cast<const unsigned char*>(data);
  const auto& t = kCrc.t;
  crc = ~crc;
  while (size >= 8) {
    const std::uint32_t lo = load_le32(p) ^ crc, hi = load_le32(p + 4);
    crc = t[7][lo & 0xFFU] ^ t[6][(lo >> 8) & 0xFFU] ^ t[5][(lo >> 16) & 0xFFU] ^ t[4][lo >> 24] ^
          t[3][hi & 0xFFU] ^ t[2][(hi >> 8) & 0xFFU] ^ t[1][(hi >> 16) & 0xFFU] ^ t[0][hi >> 24];
    p += 8;
    size -= 8;
  }
  while (size--) crc = t[0][(crc ^ *p++) & 0xFFU] ^ (crc >> 8);
  return ~crc;
}

std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ULL;
  }
  return h;
}

// ---------------------------------------------------------------------------------------------
// Little-endian encoding and the archives that walk the state (one walk for saving and loading,
// so the two cannot disagree on the layout).

namespace {

constexpr std::uint32_t kByteOrderMark = 0x01020304U;
constexpr std::uint32_t kKindWords = 1;  // a table of 64-bit words (f64 or i64 by column)
constexpr std::uint32_t kKindBytes = 2;  // raw bytes (text, flags)
// magic 8, version 4, byte-order mark 4, file size 8, step 8, time 8, scenario hash 8, specimen
// fingerprint 8, section count 4, writer length 4.
constexpr std::size_t kFixedHeader = 64;
constexpr std::size_t kTrailer = 4;

struct Out {
  std::string buf;
  void u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) buf.push_back(static_cast<char>((v >> (8 * k)) & 0xFFU));
  }
  void u64(std::uint64_t v) {
    if constexpr (std::endian::native == std::endian::little) {
      char b[8];
      std::memcpy(b, &v, 8);
      buf.append(b, 8);
    } else {
      for (int k = 0; k < 8; ++k) buf.push_back(static_cast<char>((v >> (8 * k)) & 0xFFU));
    }
  }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void bytes(const void* p, std::size_t n) { buf.append(static_cast<const char*>(p), n); }
  void put_u32_at(std::size_t at, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) buf[at + k] = static_cast<char>((v >> (8 * k)) & 0xFFU);
  }
  void put_u64_at(std::size_t at, std::uint64_t v) {
    for (int k = 0; k < 8; ++k) buf[at + k] = static_cast<char>((v >> (8 * k)) & 0xFFU);
  }
};

// One record of a table, written.
struct SaveRecord {
  Out& o;
  std::uint32_t words = 0;
  void f(double v) {
    o.f64(v);
    ++words;
  }
  void i(std::int64_t v) {
    o.u64(static_cast<std::uint64_t>(v));
    ++words;
  }
  void b(bool v) { i(v ? 1 : 0); }
  void u8(std::uint8_t v) { i(v); }
  void v(const Vec3& x) {
    f(x.x());
    f(x.y());
    f(x.z());
  }
  void q(const Quat& x) {
    f(x.x());
    f(x.y());
    f(x.z());
    f(x.w());
  }
};

// One record of a table, read.
struct LoadRecord {
  const unsigned char* p;
  std::uint64_t next() {
    const std::uint64_t w = load_le64(p);
    p += 8;
    return w;
  }
  void f(double& v) { v = std::bit_cast<double>(next()); }
  void i(std::int64_t& v) { v = static_cast<std::int64_t>(next()); }
  void b(bool& v) { v = next() != 0; }
  void u8(std::uint8_t& v) { v = static_cast<std::uint8_t>(next()); }
  void v(Vec3& x) {
    f(x.x());
    f(x.y());
    f(x.z());
  }
  void q(Quat& x) {
    f(x.x());
    f(x.y());
    f(x.z());
    f(x.w());
  }
};

class Saver {
 public:
  static constexpr bool loading = false;
  explicit Saver(Out& o) : o_(o) {}
  std::uint32_t sections() const { return sections_; }

  // n records of `width` words: fn(record, i).
  template <typename Fn>
  void table(const std::string& name, std::size_t n, std::uint32_t width, Fn&& fn) {
    header(name, kKindWords, width, n);
    for (std::size_t i = 0; i < n; ++i) {
      SaveRecord r{o_};
      fn(r, i);
      if (r.words != width)
        throw std::logic_error(
            fmt::format("checkpoint section '{}': {} words, declared {}", name, r.words, width));
    }
  }
  // A vector whose length the checkpoint sets: fn(record, element).
  template <typename Vec, typename Fn>
  void list(const std::string& name, const Vec& v, std::uint32_t width, Fn&& fn) {
    table(name, v.size(), width, [&](SaveRecord& r, std::size_t i) { fn(r, v[i]); });
  }
  template <typename Fn>
  void record(const std::string& name, std::uint32_t width, Fn&& fn) {
    table(name, 1, width, [&](SaveRecord& r, std::size_t) { fn(r); });
  }
  void text(const std::string& name, const std::string& s) {
    header(name, kKindBytes, 1, s.size());
    o_.bytes(s.data(), s.size());
  }
  // Text that must equal the restoring side's (e.g. the history's columns).
  void expect_text(const std::string& name, const std::string& s) { text(name, s); }
  void bytes(const std::string& name, const std::vector<std::uint8_t>& v) {
    header(name, kKindBytes, 1, v.size());
    o_.bytes(v.data(), v.size());
  }

 private:
  void header(const std::string& name, std::uint32_t kind, std::uint32_t width, std::size_t n) {
    o_.u32(static_cast<std::uint32_t>(name.size()));
    o_.bytes(name.data(), name.size());
    o_.u32(kind);
    o_.u32(width);
    o_.u64(n);
    ++sections_;
  }
  Out& o_;
  std::uint32_t sections_ = 0;
};

struct Section {
  std::uint32_t kind = 0, width = 0;
  std::uint64_t count = 0;
  std::size_t offset = 0;
};

// A whole file in memory, its framing checked.
struct Parsed {
  std::string data;
  CheckpointHeader header;
  std::map<std::string, Section> sections;
};

// Thrown inside parsing and restoring; turned into "checkpoint 'FILE' rejected: REASON".
struct Reject {
  std::string reason;
};

class Loader {
 public:
  static constexpr bool loading = true;
  Loader(const Parsed& f, bool apply) : f_(f), apply_(apply) {}
  bool applying() const { return apply_; }

  template <typename Fn>
  void table(const std::string& name, std::size_t n, std::uint32_t width, Fn&& fn) {
    const Section& s = find(name, kKindWords);
    if (s.width != width || s.count != n)
      throw Reject{fmt::format(
          "section '{}' holds {} records of {} words; this specimen needs {} of {} (a different "
          "specimen or format)",
          name, s.count, s.width, n, width)};
    if (!apply_) return;
    LoadRecord r{reinterpret_cast<const unsigned char*>(f_.data.data()) + s.offset};
    for (std::size_t i = 0; i < n; ++i) fn(r, i);
  }
  template <typename Vec, typename Fn>
  void list(const std::string& name, Vec& v, std::uint32_t width, Fn&& fn) {
    const Section& s = find(name, kKindWords);
    if (s.width != width)
      throw Reject{
          fmt::format("section '{}' has records of {} words, expected {}", name, s.width, width)};
    if (!apply_) return;
    v.assign(static_cast<std::size_t>(s.count), typename Vec::value_type{});
    LoadRecord r{reinterpret_cast<const unsigned char*>(f_.data.data()) + s.offset};
    for (auto& e : v) fn(r, e);
  }
  template <typename Fn>
  void record(const std::string& name, std::uint32_t width, Fn&& fn) {
    table(name, 1, width, [&](LoadRecord& r, std::size_t) { fn(r); });
  }
  void text(const std::string& name, std::string& s) {
    const Section& sec = find(name, kKindBytes);
    if (apply_) s.assign(f_.data.data() + sec.offset, static_cast<std::size_t>(sec.count));
  }
  void expect_text(const std::string& name, const std::string& expected) {
    const Section& sec = find(name, kKindBytes);
    if (std::string_view(f_.data.data() + sec.offset, static_cast<std::size_t>(sec.count)) !=
        expected)
      throw Reject{fmt::format("section '{}' differs from this run's ('{}' expected)", name,
                               expected.substr(0, 200))};
  }
  void bytes(const std::string& name, std::vector<std::uint8_t>& v) {
    const Section& sec = find(name, kKindBytes);
    if (sec.count != v.size())
      throw Reject{
          fmt::format("section '{}' holds {} bytes, expected {}", name, sec.count, v.size())};
    if (apply_ && !v.empty()) std::memcpy(v.data(), f_.data.data() + sec.offset, v.size());
  }

 private:
  const Section& find(const std::string& name, std::uint32_t kind) const {
    const auto it = f_.sections.find(name);
    if (it == f_.sections.end()) throw Reject{fmt::format("section '{}' is missing", name)};
    if (it->second.kind != kind)
      throw Reject{
          fmt::format("section '{}' has kind {}, expected {}", name, it->second.kind, kind)};
    return it->second;
  }
  const Parsed& f_;
  bool apply_;
};

std::string join(const std::vector<std::string>& v, char sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += sep;
    s += v[i];
  }
  return s;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  if (s.empty()) return out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = s.find(sep, start);
    out.push_back(s.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The state, section by section (docs/checkpoint.md lists the same).

struct CheckpointAccess {
  template <typename R, typename P>
  static void point(R& r, P& p) {  // LocalPointState: 11 words
    r.f(p.fn);
    r.v(p.fs);
    r.f(p.un);
    r.v(p.us);
    r.f(p.un_max);
    r.f(p.us_max_sq);
    r.f(p.damage);
  }

  template <typename Ar, typename C>
  static void contact_state(Ar& ar, const std::string& name, C& c) {
    ar.table(name, c.normal.size(), 17, [&](auto& r, std::size_t i) {
      r.v(c.normal[i]);
      r.v(c.tangent[i]);
      r.v(c.force_b[i]);
      r.v(c.torque_b[i]);
      r.v(c.torque_a[i]);
      r.f(c.dissipated_damage[i]);
      r.f(c.dissipated_friction[i]);
    });
    ar.table(name + ".points", static_cast<std::size_t>(c.point.size()), 9,
             [&](auto& r, std::size_t i) {
               const auto m = static_cast<Index>(i);
               c.point.for_each_history(m, [&](auto& v) { r.f(v); });
             });
  }

  template <typename Ar, typename S>
  static void simulation(Ar& ar, S& s) {
    auto& b = s.bodies_;
    const std::size_t nb = b.position.size();
    ar.table("bodies", nb, 22, [&](auto& r, std::size_t i) {
      r.v(b.position[i]);
      r.v(b.velocity[i]);
      r.v(b.angular_velocity[i]);
      r.q(b.orientation[i]);
      r.v(b.angular_momentum[i]);
      r.v(b.force[i]);
      r.v(b.torque[i]);
    });
    ar.table("bodies.step", nb, 3, [&](auto& r, std::size_t i) {
      r.f(s.body_damping_work_[i]);
      r.f(s.body_kinetic_[i]);
      r.i(s.body_jumped_[i]);
    });
    contact_state(ar, "contacts", s.contacts_);
    for (std::size_t k = 0; k < s.interface_states_.size(); ++k)
      contact_state(ar, fmt::format("interface.{}", k), s.interface_states_[k]);
    ar.table("nodes", s.node_states_.size(), 35, [&](auto& r, std::size_t j) {
      auto& n = s.node_states_[j];
      r.f(n.axial_force);
      r.v(n.shear_force);
      r.v(n.bending_moment);
      r.f(n.twisting_moment);
      r.f(n.plastic_elongation);
      r.b(n.yielded);
      r.v(n.displacement);
      r.v(n.rotation);
      auto& f = s.node_forces_[j];
      r.v(f.force_a);
      r.v(f.torque_a);
      r.v(f.force_b);
      r.v(f.torque_b);
      r.v(f.position);
      r.v(f.axis);
      r.f(f.dissipated);
    });
    ar.table("plates", s.plates_.size(), 8, [&](auto& r, std::size_t p) {
      auto& pl = s.plates_[p];
      r.f(pl.displacement);
      r.v(pl.force);
      r.f(pl.work);
      r.i(pl.contacts_active);
      r.f(s.plate_force_prev_[p]);
      r.f(s.plate_displacement_prev_[p]);
    });
    auto& pc = s.plate_contacts_;
    ar.table("plate_contacts", pc.state.size(), 21, [&](auto& r, std::size_t k) {
      point(r, pc.state[k]);
      r.v(pc.force[k]);
      r.v(pc.torque[k]);
      r.f(pc.strain_energy[k]);
      r.f(pc.dissipated_friction[k]);
      r.u8(pc.active[k]);
      r.f(pc.entry_opening[k]);
    });
    ar.table("pulled_bars", s.pulled_.size(), 7, [&](auto& r, std::size_t k) {
      auto& pb = s.pulled_[k];
      r.f(pb.displacement);
      r.v(pb.force);
      r.f(pb.work);
      r.f(pb.last_step);
      r.f(s.pulled_force_prev_[k]);
    });
    ar.record("solver", 11, [&](auto& r) {
      r.f(s.time_);
      r.i(s.steps_);
      r.f(s.dt_);
      r.f(s.damping_);
      auto& e = s.energy_;
      r.f(e.external_work);
      r.f(e.strain);
      r.f(e.kinetic);
      r.f(e.damage);
      r.f(e.friction);
      r.f(e.damping);
      r.f(e.plastic);
    });
    // loading.adaptive_rate's controller (solver/loading_rate.hpp); 1, 0, 0 when off.
    ar.record("loading_rate", 3, [&](auto& r) {
      r.f(s.loading_rate_.st_.factor);
      r.f(s.loading_rate_.st_.work);
      r.f(s.loading_rate_.st_.damage);
    });
  }

  template <typename Ar, typename H>
  static void history(Ar& ar, H& h) {
    ar.expect_text("history.columns", join(h.columns_, ','));
    const auto width = static_cast<std::uint32_t>(h.columns_.size());
    ar.list("history", h.rows_, width, [&](auto& r, auto& row) {
      if constexpr (Ar::loading) row.resize(width);
      for (std::size_t j = 0; j < width; ++j) r.f(row[j]);
    });
  }

  template <typename Ar, typename W>
  static void snapshots(Ar& ar, W& w) {
    const std::pair<const char*, decltype(&w.particle_series_)> series[] = {
        {"particles", &w.particle_series_}, {"facets", &w.facet_series_}, {"bars", &w.bar_series_}};
    for (const auto& [kind, list] : series) {
      const std::string name = fmt::format("snapshots.{}", kind);
      ar.list(name, *list, 1, [](auto& r, auto& e) { r.f(e.first); });
      if constexpr (Ar::loading) {
        std::string names;
        ar.text(name + ".files", names);
        if (ar.applying()) {
          const std::vector<std::string> files = split(names, '\n');
          if (files.size() != list->size())
            throw Reject{fmt::format("section '{}.files' lists {} files for {} times", name,
                                     files.size(), list->size())};
          for (std::size_t k = 0; k < files.size(); ++k) (*list)[k].second = files[k];
        }
      } else {
        std::vector<std::string> files;
        for (const auto& e : *list) files.push_back(e.second);
        ar.text(name + ".files", join(files, '\n'));
      }
    }
  }

  template <typename Ar, typename C>
  static void cracks(Ar& ar, C& c) {
    ar.bytes("cracks.broken", c.broken_);
    ar.list("cracks", c.rows_, 7, [](auto& r, auto& row) {
      r.v(row.position);
      r.f(row.area);
      r.i(row.step);
      r.f(row.deflection);
      r.f(row.load);
    });
  }

  template <typename Ar, typename L>
  static void loop(Ar& ar, L& l) {
    ar.record("run", 8, [&](auto& r) {
      r.f(l.peak);
      r.f(l.peak_load);
      r.f(l.displacement_at_peak);
      r.f(l.kinetic_over_strain_at_peak);
      r.f(l.wall_seconds);
      r.f(l.loop_seconds);
      r.i(l.history_every);
      r.i(l.snapshot_every);
    });
  }

  template <typename Ar>
  static void save_parts(Ar& ar, const CheckpointParts& p) {
    // Condensed contacts' histories as if visited (elastic_condensation.hpp): what the file holds
    // does not depend on the condensation, and a restart needs no kinematics of the last step.
    p.sim->catch_up_condensed_points();
    simulation(ar, static_cast<const Simulation&>(*p.sim));
    if (p.history) history(ar, static_cast<const History&>(*p.history));
    if (p.snapshots) snapshots(ar, static_cast<const SnapshotWriter&>(*p.snapshots));
    if (p.cracks) cracks(ar, static_cast<const CrackRecord&>(*p.cracks));
    if (p.loop) loop(ar, static_cast<const LoopState&>(*p.loop));
  }
  // After the state is in: which contacts are intact follows from the points' damage, and none is
  // condensed (their histories were complete when saved).
  static void after_restore(Simulation& s) {
    if (!s.condensation_.sums.empty())
      s.condensation_.reset_flags(s.specimen_.contacts, s.contacts_.point.damage());
  }
  template <typename Ar>
  static void load_parts(Ar& ar, const CheckpointParts& p) {
    simulation(ar, *p.sim);
    if (p.history) history(ar, *p.history);
    if (p.snapshots) snapshots(ar, *p.snapshots);
    if (p.cracks) cracks(ar, *p.cracks);
    if (p.loop) loop(ar, *p.loop);
  }

  static std::uint64_t fingerprint(const Simulation& s) {
    Out o;
    const auto counts = {static_cast<Index>(s.bodies_.size()),
                         s.concrete_count(),
                         s.specimen_.contacts.contact_count(),
                         s.specimen_.contacts.point_count(),
                         s.plate_contacts_.size(),
                         static_cast<Index>(s.nodes_.size()),
                         static_cast<Index>(s.interface_states_.size()),
                         static_cast<Index>(s.pulled_.size())};
    for (const Index c : counts) o.u64(static_cast<std::uint64_t>(c));
    SaveRecord r{o};
    const Bodies& b = s.bodies_;
    for (Index i = 0; i < b.size(); ++i) {
      r.v(b.position0[i]);
      r.q(b.orientation0[i]);
      r.f(b.mass[i]);
      r.v(b.inertia[i]);
      r.f(b.radius[i]);
    }
    const auto network = [&](const ContactNetwork& nw) {
      o.u64(static_cast<std::uint64_t>(nw.point_count()));
      for (Index c = 0; c < nw.contact_count(); ++c) {
        r.i(nw.particle_a[c]);
        r.i(nw.particle_b[c]);
        r.i(nw.point_begin[c]);
      }
      for (Index m = 0; m < nw.point_count(); ++m) {
        r.v(nw.point_position0[m]);
        r.f(nw.constants[m].kn);
        r.f(nw.constants[m].ks);
        r.f(nw.constants[m].fn_max);
        r.f(nw.constants[m].c_max);
      }
    };
    network(s.specimen_.contacts);
    for (const auto& ic : s.specimen_.interfaces) network(ic.net);
    const PlateContacts& pc = s.plate_contacts_;
    for (Index k = 0; k < pc.size(); ++k) {
      r.i(pc.particle[k]);
      r.v(pc.point0[k]);
      r.f(pc.constants[k].kn);
      r.f(pc.constants[k].ks);
    }
    return fnv1a64(o.buf);
  }
};

std::uint64_t specimen_fingerprint(const Simulation& sim) {
  return CheckpointAccess::fingerprint(sim);
}

// ---------------------------------------------------------------------------------------------
// Files.

std::string encode_checkpoint(const CheckpointParts& parts, std::uint64_t scenario_hash) {
  if (!parts.sim) throw std::logic_error("encode_checkpoint: no simulation");
  const Simulation& sim = *parts.sim;
  Out o;
  o.bytes(kCheckpointMagic, 8);
  o.u32(kCheckpointVersion);
  o.u32(kByteOrderMark);
  const std::size_t size_at = o.buf.size();
  o.u64(0);  // the file size, set below
  o.u64(static_cast<std::uint64_t>(sim.steps()));
  o.f64(sim.time());
  o.u64(scenario_hash);
  o.u64(specimen_fingerprint(sim));
  const std::size_t sections_at = o.buf.size();
  o.u32(0);  // the section count, set below
  const std::string writer = fmt::format("rcdem {} ({})", build_version(), build_git_hash());
  o.u32(static_cast<std::uint32_t>(writer.size()));
  o.bytes(writer.data(), writer.size());
  Saver saver(o);
  CheckpointAccess::save_parts(saver, parts);
  o.put_u32_at(sections_at, saver.sections());
  o.put_u64_at(size_at, o.buf.size() + kTrailer);
  o.u32(crc32(o.buf.data(), o.buf.size()));
  return std::move(o.buf);
}

namespace {

std::string read_whole(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Reject{fmt::format("cannot open it: {}", std::strerror(errno))};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    throw Reject{fmt::format("cannot read it: {}", std::strerror(err))};
  }
  std::string data(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::read(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw Reject{fmt::format("cannot read it: {}", std::strerror(err))};
    }
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  data.resize(done);
  return data;
}

Parsed parse(const fs::path& file) {
  Parsed f;
  f.data = read_whole(file);
  const std::string& d = f.data;
  const auto* u = reinterpret_cast<const unsigned char*>(d.data());
  if (d.size() < kFixedHeader + kTrailer)
    throw Reject{fmt::format("truncated: {} bytes, shorter than the smallest checkpoint ({})",
                             d.size(), kFixedHeader + kTrailer)};
  if (std::memcmp(d.data(), kCheckpointMagic, 8) != 0)
    throw Reject{"not an rcdem checkpoint (it does not start with 'RCDEMCKP')"};
  CheckpointHeader& h = f.header;
  h.version = load_le32(u + 8);
  const std::uint32_t bom = load_le32(u + 12);
  if (bom != kByteOrderMark)
    throw Reject{fmt::format("byte-order mark {:#010x}, expected {:#010x}: not little-endian", bom,
                             kByteOrderMark)};
  if (h.version != kCheckpointVersion)
    throw Reject{h.version > kCheckpointVersion
                     ? fmt::format("format version {} is newer than this rcdem reads ({}); "
                                   "resume it with the rcdem that wrote it",
                                   h.version, kCheckpointVersion)
                 : h.version >= 1
                     ? fmt::format("format version {} is older than this rcdem reads ({}); "
                                   "resume it with the rcdem that wrote it",
                                   h.version, kCheckpointVersion)
                     : fmt::format("unknown format version {}", h.version)};
  h.file_size = load_le64(u + 16);
  if (d.size() < h.file_size)
    throw Reject{fmt::format("truncated: {} of {} bytes", d.size(), h.file_size)};
  if (d.size() > h.file_size)
    throw Reject{fmt::format("{} bytes where its header says {}: data after the end", d.size(),
                             h.file_size)};
  const std::uint32_t stored = load_le32(u + d.size() - kTrailer);
  const std::uint32_t computed = crc32(d.data(), d.size() - kTrailer);
  if (stored != computed)
    throw Reject{fmt::format(
        "checksum mismatch (stored CRC-32 {:08x}, computed {:08x}): the file is corrupted", stored,
        computed)};
  h.step = static_cast<std::int64_t>(load_le64(u + 24));
  h.time = std::bit_cast<double>(load_le64(u + 32));
  h.scenario_hash = load_le64(u + 40);
  h.specimen_fingerprint = load_le64(u + 48);
  h.sections = load_le32(u + 56);
  const std::size_t end = d.size() - kTrailer;
  std::size_t at = 60;
  const auto need = [&](std::size_t n, const char* what) {
    if (n > end - at) throw Reject{fmt::format("malformed: {} runs past the end", what)};
  };
  need(4, "the writer");
  const std::uint32_t wlen = load_le32(u + at);
  at += 4;
  need(wlen, "the writer");
  h.writer.assign(d.data() + at, wlen);
  at += wlen;
  for (std::uint32_t k = 0; k < h.sections; ++k) {
    need(4, "a section header");
    const std::uint32_t nlen = load_le32(u + at);
    at += 4;
    need(static_cast<std::size_t>(nlen) + 16, "a section header");
    std::string name(d.data() + at, nlen);
    at += nlen;
    Section s;
    s.kind = load_le32(u + at);
    s.width = load_le32(u + at + 4);
    s.count = load_le64(u + at + 8);
    at += 16;
    std::uint64_t bytes = 0;
    if (s.kind == kKindWords) {
      if (s.width != 0 && s.count > (end - at) / (8ULL * s.width))
        throw Reject{fmt::format("malformed: section '{}' runs past the end", name)};
      bytes = 8ULL * s.width * s.count;
    } else if (s.kind == kKindBytes) {
      bytes = s.count;
    } else {
      throw Reject{fmt::format("malformed: section '{}' has unknown kind {}", name, s.kind)};
    }
    need(static_cast<std::size_t>(bytes), "a section");
    s.offset = at;
    at += static_cast<std::size_t>(bytes);
    f.sections[name] = s;
  }
  if (at != end) throw Reject{"malformed: bytes between the last section and the checksum"};
  return f;
}

std::string rejected(const fs::path& file, const std::string& reason) {
  return fmt::format("checkpoint '{}' rejected: {}", file.string(), reason);
}

}  // namespace

CheckpointHeader inspect_checkpoint(const fs::path& file) {
  try {
    return parse(file).header;
  } catch (const Reject& r) {
    throw Error(rejected(file, r.reason));
  }
}

CheckpointHeader restore_checkpoint(const fs::path& file, const CheckpointParts& parts,
                                    std::uint64_t scenario_hash) {
  if (!parts.sim) throw std::logic_error("restore_checkpoint: no simulation");
  try {
    const Parsed f = parse(file);
    if (f.header.scenario_hash != scenario_hash)
      throw Reject{fmt::format(
          "written for other scenario inputs (hash {:016x}; this scenario and its includes hash "
          "to {:016x}): the scenario or a fragment it includes changed since the run started",
          f.header.scenario_hash, scenario_hash)};
    const std::uint64_t fp = specimen_fingerprint(*parts.sim);
    if (f.header.specimen_fingerprint != fp)
      throw Reject{fmt::format(
          "written for another specimen (fingerprint {:016x}, the regenerated one is {:016x}): "
          "the generator gives a different specimen (another rcdem version?)",
          f.header.specimen_fingerprint, fp)};
    Loader check(f, false);
    CheckpointAccess::load_parts(check, parts);
    Loader apply(f, true);
    CheckpointAccess::load_parts(apply, parts);
    CheckpointAccess::after_restore(*parts.sim);
    return f.header;
  } catch (const Reject& r) {
    throw Error(rejected(file, r.reason));
  }
}

fs::path checkpoint_path(const fs::path& dir, std::int64_t step) {
  return dir / fmt::format("checkpoint_{:012d}.rcp", step);
}

std::vector<CheckpointFile> list_checkpoints(const fs::path& dir) {
  std::vector<CheckpointFile> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    constexpr std::string_view prefix = "checkpoint_", suffix = ".rcp";
    if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.empty() || digits.size() > 18 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    out.push_back({e.path(), std::stoll(digits)});
  }
  std::sort(out.begin(), out.end(),
            [](const CheckpointFile& a, const CheckpointFile& b) { return a.step > b.step; });
  return out;
}

namespace {

bool is_checkpoint_temporary(const std::string& name) {
  return name.rfind("checkpoint_", 0) == 0 && name.find(".rcp.tmp.") != std::string::npos;
}

void sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);  // best effort: some file systems refuse it on directories
  ::close(fd);
}

}  // namespace

fs::path write_checkpoint(const fs::path& dir, const CheckpointParts& parts,
                          std::uint64_t scenario_hash, int keep) {
  const std::string data = encode_checkpoint(parts, scenario_hash);
  const fs::path path = checkpoint_path(dir, parts.sim->steps());
  const fs::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
  if (const int err = try_write_file_atomically(path, data))
    fail("cannot write checkpoint '{}': {}; the earlier checkpoints are kept", path.string(),
         std::strerror(err));
  sync_directory(dir);
  // Keep the newest `keep`; drop what an interrupted write left.
  const std::vector<CheckpointFile> all = list_checkpoints(dir);
  std::error_code ec;
  for (std::size_t k = static_cast<std::size_t>(std::max(keep, 1)); k < all.size(); ++k)
    fs::remove(all[k].path, ec);
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (is_checkpoint_temporary(name) && e.path() != tmp) fs::remove(e.path(), ec);
  }
  return path;
}

RestoreReport restore_latest_checkpoint(const fs::path& dir, const CheckpointParts& parts,
                                        std::uint64_t scenario_hash) {
  RestoreReport report;
  const std::vector<CheckpointFile> all = list_checkpoints(dir);
  if (all.empty())
    fail("no checkpoint in '{}' (checkpoint_*.rcp): the run stopped before its first checkpoint",
         dir.string());
  for (const CheckpointFile& c : all) {
    try {
      report.header = restore_checkpoint(c.path, parts, scenario_hash);
      report.file = c.path;
      break;
    } catch (const Error& e) {
      report.rejected.emplace_back(e.what());
    }
  }
  if (report.file.empty()) {
    std::string why;
    for (const auto& r : report.rejected) why += "; " + r;
    fail("no usable checkpoint in '{}'{}", dir.string(), why);
  }
  // The files passed over (damaged, or newer than the state now restored) would be taken again
  // by the next resume or kept instead of good ones: set them aside, not deleted.
  for (auto& line : report.rejected)
    for (const CheckpointFile& c : all)
      if (c.step > report.header.step && line.find(c.path.string()) != std::string::npos) {
        std::error_code ec;
        const fs::path aside = c.path.string() + ".rejected";
        fs::rename(c.path, aside, ec);
        if (!ec) line += fmt::format(" (set aside as '{}')", aside.filename().string());
      }
  return report;
}

void remove_checkpoints(const fs::path& dir) {
  std::error_code ec;
  for (const CheckpointFile& c : list_checkpoints(dir)) fs::remove(c.path, ec);
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (is_checkpoint_temporary(e.path().filename().string())) fs::remove(e.path(), ec);
}

}  // namespace rcdem::io
