#pragma once
// The archives that walk the state for run/checkpoint.cpp: Saver writes a section per call,
// Loader checks and reads it back, and both take the columns the state structs name in their
// serialize() (core/archive.hpp). One walk serves both, so the two cannot disagree on the layout;
// a table's width comes from its columns' types, never from a count written by hand.
//
// A section: u32 name length, the name, u32 kind, u32 width, u64 count, the payload
// (docs/checkpoint.md). Kind 1: `count` records of `width` little-endian 64-bit words; kind 2:
// `count` raw bytes.
#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/state/bodies.hpp"  // Quat

namespace rcdem::io::checkpoint_detail {

inline constexpr std::uint32_t kKindWords = 1;  // a table of 64-bit words (f64 or i64 by column)
inline constexpr std::uint32_t kKindBytes = 2;  // raw bytes (text, flags)

inline std::uint32_t load_le32(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}
inline std::uint64_t load_le64(const unsigned char* p) {
  return static_cast<std::uint64_t>(load_le32(p)) | static_cast<std::uint64_t>(load_le32(p + 4))
                                                        << 32;
}

// Thrown while parsing and restoring; turned into "checkpoint 'FILE' rejected: REASON".
struct Reject {
  std::string reason;
};

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

// put(x) for every column type: scalars are one word each (reals as f64, integers and flags as
// i64), Vec3 three, Quat four (x, y, z, w), anything else its archive_fields (found by ADL).
template <class Derived>
struct Record {
  // A named value (core/archive.hpp): the name matters only to an archive that describes.
  template <class T>
  void put(Named<T> n) {
    auto& d = static_cast<Derived&>(*this);
    d.enter(n.name, n.unit);
    put(n.value);
    d.leave();
  }
  void enter(const char*, const char*) {}
  void leave() {}
  template <class T>
  void put(T& x) {
    auto& d = static_cast<Derived&>(*this);
    using U = std::remove_const_t<T>;
    if constexpr (std::is_same_v<U, Vec3>) {
      d.word(x.x());
      d.word(x.y());
      d.word(x.z());
    } else if constexpr (std::is_same_v<U, Quat>) {
      d.word(x.x());
      d.word(x.y());
      d.word(x.z());
      d.word(x.w());
    } else if constexpr (std::is_arithmetic_v<U>) {
      d.word(x);
    } else {
      archive_fields(d, x);
    }
  }
};

struct SaveRecord : Record<SaveRecord> {
  Out& o;
  explicit SaveRecord(Out& out) : o(out) {}
  template <class T>
  void word(const T& v) {
    if constexpr (std::is_floating_point_v<T>)
      o.f64(v);
    else
      o.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(v)));
  }
};

struct LoadRecord : Record<LoadRecord> {
  const unsigned char* p;
  explicit LoadRecord(const unsigned char* at) : p(at) {}
  template <class T>
  void word(T& v) {
    const std::uint64_t w = load_le64(p);
    p += 8;
    if constexpr (std::is_floating_point_v<T>)
      v = std::bit_cast<double>(w);
    else if constexpr (std::is_same_v<T, bool>)
      v = w != 0;
    else
      v = static_cast<T>(static_cast<std::int64_t>(w));
  }
};

struct CountRecord : Record<CountRecord> {
  std::uint32_t words = 0;
  template <class T>
  void word(const T&) {
    ++words;
  }
};

template <class T>
struct Unnamed {
  using type = T;
};
template <class T>
struct Unnamed<Named<T>> {
  using type = T;
};

// The words one value of type T (or a Named<T>) takes.
template <class T>
std::uint32_t words_of() {
  CountRecord c;
  std::remove_const_t<typename Unnamed<T>::type> v{};
  c.put(v);
  return c.words;
}
// ... and one record of the given columns (callables of the record's index).
template <class... Columns>
std::uint32_t record_width() {
  return (words_of<std::remove_reference_t<std::invoke_result_t<Columns, std::size_t>>>() + ...);
}
// ... and one element of a list with the given members (NamedMember, core/archive.hpp).
template <class E, class... Members>
std::uint32_t element_width() {
  return (
      words_of<
          std::remove_reference_t<decltype(std::declval<E&>().*(std::declval<Members>().m))>>() +
      ...);
}

template <class R, class E, class... Members>
void put_element(R& r, E& e, Members... m) {
  (r.put(named(m.name, m.unit, e.*(m.m))), ...);
}

// Column i of a table as a named value.
template <class R, class Col>
void put_column(R& r, const Col& c, std::size_t i) {
  r.put(named(c.name, c.unit, c(i)));
}

// A section of an image: its kind, width, record count and where its payload starts.
struct Section {
  std::uint32_t kind = 0, width = 0;
  std::uint64_t count = 0;
  std::size_t offset = 0;
};

class Saver {
 public:
  static constexpr bool loading = false;
  explicit Saver(Out& o) : o_(o) {}
  // The sections written, in order (what parse_image would read back).
  const std::vector<std::pair<std::string, Section>>& sections() const { return sections_; }

  // n records, record i being column(i) for each column in turn.
  template <class... Columns>
  void table(const std::string& name, std::size_t n, Columns... columns) {
    header(name, kKindWords, record_width<Columns...>(), n);
    SaveRecord r{o_};
    for (std::size_t i = 0; i < n; ++i) (put_column(r, columns, i), ...);
  }
  template <class... Fields>
  void record(const std::string& name, const Fields&... fields) {
    header(name, kKindWords, (words_of<Fields>() + ...), 1);
    SaveRecord r{o_};
    (r.put(fields), ...);
  }
  // A vector whose length the file sets, an element's `members` in turn.
  template <class Vec, class... Members>
  void list(const std::string& name, const Vec& v, Members... members) {
    using E = typename Vec::value_type;
    header(name, kKindWords, element_width<E, Members...>(), v.size());
    SaveRecord r{o_};
    for (const E& e : v) put_element(r, e, members...);
  }
  // Rows of reals, `width` each (a width that depends on the run: the history's columns).
  void rows(const std::string& name, const std::vector<std::vector<double>>& rows,
            std::size_t width) {
    header(name, kKindWords, static_cast<std::uint32_t>(width), rows.size());
    SaveRecord r{o_};
    for (const auto& row : rows)
      for (std::size_t j = 0; j < width; ++j) r.put(row[j]);
  }
  // (number, text) pairs: the numbers as a table `name`, the texts as lines of `name`.files.
  template <class Vec, class First, class Second>
  void series(const std::string& name, const Vec& v, First first, Second second) {
    list(name, v, first);
    std::string lines;
    for (std::size_t k = 0; k < v.size(); ++k) (lines += k ? "\n" : "") += v[k].*second;
    text(name + ".files", lines);
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
    sections_.push_back({name, Section{kind, width, n, o_.buf.size()}});
  }
  Out& o_;
  std::vector<std::pair<std::string, Section>> sections_;
};

// Names each word of a record: the path of the names around it ("history.fs.t1") and the
// innermost unit given, in order (checkpoint_layout).
struct DescribeRecord : Record<DescribeRecord> {
  std::vector<CheckpointColumn>* out;
  std::string section;
  std::vector<std::pair<std::string, std::string>> path;  // (name, unit) from the outside in
  explicit DescribeRecord(std::vector<CheckpointColumn>& o, std::string s)
      : out(&o), section(std::move(s)) {}
  void enter(const char* name, const char* unit) { path.emplace_back(name, unit); }
  void leave() { path.pop_back(); }
  template <class T>
  void word(const T&) {
    std::string name, unit;
    for (const auto& [n, u] : path) {
      name += (name.empty() ? "" : ".") + n;
      if (!u.empty()) unit = u;
    }
    if (!out->empty() && out->back().section == section && out->back().name == name) {
      ++out->back().words;
      return;
    }
    out->push_back({section, name, unit, 1, std::is_floating_point_v<T>});
  }
};

// The layout of what a Saver writes: every section's columns, named, with their units and words
// (a table's from its first record: an empty table describes nothing).
class Describer {
 public:
  static constexpr bool loading = false;
  explicit Describer(std::vector<CheckpointColumn>& out) : out_(out) {}

  template <class... Columns>
  void table(const std::string& name, std::size_t n, Columns... columns) {
    if (n == 0) return;
    DescribeRecord r{out_, name};
    (put_column(r, columns, 0), ...);
  }
  template <class... Fields>
  void record(const std::string& name, const Fields&... fields) {
    DescribeRecord r{out_, name};
    (r.put(fields), ...);
  }
  template <class Vec, class... Members>
  void list(const std::string& name, const Vec& v, Members... members) {
    using E = typename Vec::value_type;
    E e{};
    DescribeRecord r{out_, name};
    put_element(r, e, members...);
    (void)v;
  }
  void rows(const std::string& name, const std::vector<std::vector<double>>&, std::size_t width) {
    out_.push_back({name, "row", "", static_cast<std::uint32_t>(width), true});
  }
  template <class Vec, class First, class Second>
  void series(const std::string& name, const Vec& v, First first, Second) {
    list(name, v, first);
    text(name + ".files", "");
  }
  void text(const std::string& name, const std::string&) {
    out_.push_back({name, "text", "", 0, false});
  }
  void expect_text(const std::string& name, const std::string& s) { text(name, s); }
  void bytes(const std::string& name, const std::vector<std::uint8_t>&) {
    out_.push_back({name, "bytes", "", 0, false});
  }

 private:
  std::vector<CheckpointColumn>& out_;
};

// A whole file in memory, its framing checked.
struct Parsed {
  std::string data;
  CheckpointHeader header;
  std::map<std::string, Section> sections;
  std::vector<std::string> order;  // the sections' names in the file's order
};

// The binary format's magic, version, byte-order mark, file size, step, time, hashes, section
// count and writer: its first bytes up to the first section (run/checkpoint.cpp).
std::string image_header(const CheckpointHeader& h);
inline constexpr std::size_t kImageTrailer = 4;  // the CRC-32
inline constexpr std::size_t kImageFileSizeAt = 16, kImageSectionCountAt = 56;

// Checks an image's framing (size, magic, version, byte order, length, checksum) and reads its
// section table; throws Reject.
Parsed parse_image(std::string data);

// Reads what Saver wrote, section by section, after checking each one's kind, width and count;
// with apply = false it only checks (a first pass, so that a bad file changes nothing).
class Loader {
 public:
  static constexpr bool loading = true;
  Loader(const Parsed& f, bool apply) : f_(f), apply_(apply) {}
  bool applying() const { return apply_; }
  std::uint32_t version() const { return f_.header.version; }  // of the file being read
  // For a part that finds what it read inconsistent (a state struct cannot name Reject).
  [[noreturn]] void reject(const std::string& reason) const { throw Reject{reason}; }

  template <class... Columns>
  void table(const std::string& name, std::size_t n, Columns... columns) {
    const Section& s = find(name, kKindWords);
    const std::uint32_t width = record_width<Columns...>();
    if (s.width != width || s.count != n)
      throw Reject{fmt::format(
          "section '{}' holds {} records of {} words; this specimen needs {} of {} (a different "
          "specimen or format)",
          name, s.count, s.width, n, width)};
    if (!apply_) return;
    LoadRecord r{at(s)};
    for (std::size_t i = 0; i < n; ++i) (put_column(r, columns, i), ...);
  }
  template <class... Fields>
  void record(const std::string& name, Fields... fields) {
    const Section& s = find(name, kKindWords);
    const std::uint32_t width = (words_of<Fields>() + ...);
    if (s.width != width || s.count != 1)
      throw Reject{fmt::format("section '{}' holds {} records of {} words, expected 1 of {}", name,
                               s.count, s.width, width)};
    if (!apply_) return;
    LoadRecord r{at(s)};
    (r.put(fields), ...);
  }
  template <class Vec, class... Members>
  void list(const std::string& name, Vec& v, Members... members) {
    using E = typename Vec::value_type;
    const Section& s = find(name, kKindWords);
    const std::uint32_t width = element_width<E, Members...>();
    if (s.width != width)
      throw Reject{
          fmt::format("section '{}' has records of {} words, expected {}", name, s.width, width)};
    if (!apply_) return;
    v.assign(static_cast<std::size_t>(s.count), E{});
    LoadRecord r{at(s)};
    for (E& e : v) put_element(r, e, members...);
  }
  void rows(const std::string& name, std::vector<std::vector<double>>& rows, std::size_t width) {
    const Section& s = find(name, kKindWords);
    if (s.width != width)
      throw Reject{
          fmt::format("section '{}' has records of {} words, expected {}", name, s.width, width)};
    if (!apply_) return;
    rows.assign(static_cast<std::size_t>(s.count), std::vector<double>(width));
    LoadRecord r{at(s)};
    for (auto& row : rows)
      for (double& x : row) r.put(x);
  }
  template <class Vec, class First, class Second>
  void series(const std::string& name, Vec& v, First first, Second second) {
    list(name, v, first);
    std::string lines;
    text(name + ".files", lines);
    if (!apply_) return;
    std::vector<std::string> files;
    for (std::size_t start = 0; !lines.empty();) {
      const std::size_t end = lines.find('\n', start);
      files.push_back(lines.substr(start, end == std::string::npos ? end : end - start));
      if (end == std::string::npos) break;
      start = end + 1;
    }
    if (files.size() != v.size())
      throw Reject{fmt::format("section '{}.files' lists {} files for {} times", name, files.size(),
                               v.size())};
    for (std::size_t k = 0; k < files.size(); ++k) v[k].*second = files[k];
  }
  void text(const std::string& name, std::string& s) {
    const Section& sec = find(name, kKindBytes);
    s.assign(f_.data.data() + sec.offset, static_cast<std::size_t>(sec.count));
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
  const unsigned char* at(const Section& s) const {
    return reinterpret_cast<const unsigned char*>(f_.data.data()) + s.offset;
  }
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

}  // namespace rcdem::io::checkpoint_detail
