#include "rcdem/run/checkpoint_hdf5.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>

#include "rcdem/run/checkpoint_archive.hpp"

namespace rcdem::io::checkpoint_detail {

namespace {

constexpr const char* kFormatName = "rcdem checkpoint";

// An HDF5 identifier, closed by its kind's function when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), close_(closer) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  ~Handle() { close(); }
  operator hid_t() const { return id_; }  // NOLINT: used as the hid_t it holds
  herr_t close() { return id_ >= 0 ? close_(std::exchange(id_, -1)) : 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// Before any other HDF5 call: no clean-up at exit, where HDF5 1.10 would close again a file whose
// close failed (a full disk) and crash in it; and errors become messages, not prints.
void start_hdf5() {
  H5dont_atexit();
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

herr_t keep_innermost(unsigned n, const H5E_error2_t* e, void* out) {
  if (n == 0 && e->desc) *static_cast<std::string*>(out) = e->desc;
  return 0;
}

// Why the last HDF5 call failed, in the fewest words: a system call's own message where there
// is one ("No space left on device"), else HDF5's innermost description.
std::string hdf5_reason() {
  std::string desc;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &desc);
  const std::string key = "error message = '";
  if (const auto at = desc.find(key); at != std::string::npos) {
    const auto end = desc.find('\'', at + key.size());
    if (end != std::string::npos) return desc.substr(at + key.size(), end - at - key.size());
  }
  return desc.empty() ? "an HDF5 error" : desc;
}

// Why HDF5 could not open a file; a file cut short in the words the binary format uses.
std::string open_failure() {
  const std::string why = hdf5_reason();
  unsigned long long eof = 0, stored = 0;
  const auto at = why.find("truncated file: eof = ");
  if (at != std::string::npos &&
      std::sscanf(why.c_str() + at,
                  "truncated file: eof = %llu, sblock->base_addr = %*[^,], stored_eof = %llu", &eof,
                  &stored) == 2)
    return fmt::format("truncated: {} of {} bytes", eof, stored);
  return "not a readable HDF5 file: " + why;
}

hid_t must(hid_t id, const std::string& what) {
  if (id < 0) throw Reject{fmt::format("{}: {}", what, hdf5_reason())};
  return id;
}
void must_succeed(herr_t status, const std::string& what) {
  if (status < 0) throw Reject{fmt::format("{}: {}", what, hdf5_reason())};
}

Handle text_type() {
  Handle t{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

// ---------------------------------------------------------------------------------------------
// Attributes: scalars and texts.

void put_attribute(hid_t obj, const char* name, hid_t type, hid_t memory_type, const void* v) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle a{must(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT),
                fmt::format("cannot create attribute '{}'", name)),
           H5Aclose};
  must_succeed(H5Awrite(a, memory_type, v), fmt::format("cannot write attribute '{}'", name));
}
void put_text(hid_t obj, const char* name, const std::string& v) {
  const Handle t = text_type();
  const char* p = v.c_str();
  put_attribute(obj, name, t, t, &p);
}
template <class T>
void put_number(hid_t obj, const char* name, hid_t type, hid_t memory_type, T v) {
  put_attribute(obj, name, type, memory_type, &v);
}

Handle open_attribute(hid_t obj, const char* name, const std::string& where) {
  if (H5Aexists(obj, name) <= 0)
    throw Reject{fmt::format("malformed: {} has no attribute '{}'", where, name)};
  return {must(H5Aopen(obj, name, H5P_DEFAULT), fmt::format("cannot read attribute '{}'", name)),
          H5Aclose};
}
std::string text_attribute(hid_t obj, const char* name, const std::string& where) {
  const Handle a = open_attribute(obj, name, where);
  const Handle type{H5Aget_type(a), H5Tclose};
  if (H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) <= 0)
    throw Reject{fmt::format("malformed: {}'s attribute '{}' is not a text", where, name)};
  const Handle t = text_type();
  char* p = nullptr;
  must_succeed(H5Aread(a, t, &p), fmt::format("cannot read attribute '{}'", name));
  std::string v = p ? p : "";
  H5free_memory(p);
  return v;
}
template <class T>
T number_attribute(hid_t obj, const char* name, hid_t memory_type, const std::string& where) {
  const Handle a = open_attribute(obj, name, where);
  const Handle type{H5Aget_type(a), H5Tclose};
  const H5T_class_t c = H5Tget_class(type);
  if (c != H5T_INTEGER && c != H5T_FLOAT)
    throw Reject{fmt::format("malformed: {}'s attribute '{}' is not a number", where, name)};
  T v{};
  must_succeed(H5Aread(a, memory_type, &v), fmt::format("cannot read attribute '{}'", name));
  return v;
}

// The selection of words [offset, offset + words) of each of `count` records of `width` words:
// one column of a section's payload, in memory.
Handle record_columns(hsize_t count, hsize_t width, hsize_t offset, hsize_t words) {
  const hsize_t dims[2] = {count, width}, start[2] = {0, offset}, n[2] = {count, words};
  Handle m{H5Screate_simple(2, dims, nullptr), H5Sclose};
  H5Sselect_hyperslab(m, H5S_SELECT_SET, start, nullptr, n, nullptr);
  return m;
}

// ---------------------------------------------------------------------------------------------
// Writing.

Handle ordered(hid_t list_class) {
  Handle p{H5Pcreate(list_class), H5Pclose};
  H5Pset_link_creation_order(p, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  return p;
}

void write_words(hid_t g, const std::string& section, const Section& s, const char* payload,
                 const std::vector<const CheckpointColumn*>& columns) {
  std::uint32_t width = 0;
  for (const CheckpointColumn* c : columns) width += c->words;
  if (width != s.width && (s.count > 0 || !columns.empty()))
    throw std::logic_error(fmt::format(
        "checkpoint section '{}': columns of {} words, records of {}", section, width, s.width));
  hsize_t offset = 0;
  for (const CheckpointColumn* c : columns) {
    const hsize_t dims[2] = {s.count, c->words};
    Handle space{H5Screate_simple(c->words == 1 ? 1 : 2, dims, nullptr), H5Sclose};
    const hid_t type = c->real ? H5T_IEEE_F64LE : H5T_STD_I64LE;
    Handle d{
        must(H5Dcreate2(g, c->name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             fmt::format("cannot create dataset '{}/{}'", section, c->name)),
        H5Dclose};
    put_text(d, "unit", c->unit);
    if (s.count > 0) {
      const Handle m = record_columns(s.count, s.width, offset, c->words);
      must_succeed(H5Dwrite(d, type, m, H5S_ALL, H5P_DEFAULT, payload),
                   fmt::format("cannot write dataset '{}/{}'", section, c->name));
    }
    offset += c->words;
  }
}

// A byte section: a text as one string where it is one (no NUL), else its bytes.
void write_bytes(hid_t g, const std::string& section, const Section& s, const char* payload,
                 bool text) {
  text = text && std::memchr(payload, 0, s.count) == nullptr;
  put_text(g, "kind", text ? "text" : "bytes");
  put_number(g, "count", H5T_STD_U64LE, H5T_NATIVE_UINT64, s.count);
  const hsize_t n = s.count;
  Handle space{text ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose};
  const Handle t = text_type();
  const hid_t type = text ? hid_t{t} : H5T_STD_U8LE;
  const char* name = text ? "text" : "bytes";
  Handle d{must(H5Dcreate2(g, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                fmt::format("cannot create dataset '{}/{}'", section, name)),
           H5Dclose};
  const std::string value = text ? std::string(payload, s.count) : std::string();
  const char* p = value.c_str();  // a text is written from a NUL-terminated copy
  if (text || n > 0)
    must_succeed(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                          text ? static_cast<const void*>(&p) : payload),
                 fmt::format("cannot write dataset '{}/{}'", section, name));
}

void write_header(hid_t f, const Parsed& image) {
  const CheckpointHeader& h = image.header;
  const std::uint32_t crc = load_le32(reinterpret_cast<const unsigned char*>(
      image.data.data() + image.data.size() - kImageTrailer));
  put_text(f, "format", kFormatName);
  put_number(f, "version", H5T_STD_U32LE, H5T_NATIVE_UINT32, h.version);
  put_number(f, "step", H5T_STD_I64LE, H5T_NATIVE_INT64, h.step);
  put_number(f, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, h.time);
  put_number(f, "scenario_hash", H5T_STD_U64LE, H5T_NATIVE_UINT64, h.scenario_hash);
  put_number(f, "specimen_fingerprint", H5T_STD_U64LE, H5T_NATIVE_UINT64, h.specimen_fingerprint);
  put_text(f, "writer", h.writer);
  put_number(f, "crc32", H5T_STD_U32LE, H5T_NATIVE_UINT32, crc);
}

// The CRC-32 of bytes [from, size) of `fd`.
std::uint32_t crc_of(int fd, std::uint64_t from, std::uint64_t size) {
  std::vector<char> buf(1 << 20);
  std::uint32_t crc = 0;
  for (std::uint64_t at = from; at < size;) {
    const ssize_t n = ::pread(fd, buf.data(), std::min<std::uint64_t>(buf.size(), size - at),
                              static_cast<off_t>(at));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Reject{fmt::format("cannot read it: {}", std::strerror(errno))};
    if (n == 0) throw Reject{fmt::format("truncated: {} of {} bytes", at, size)};
    crc = crc32(buf.data(), static_cast<std::size_t>(n), crc);
    at += static_cast<std::uint64_t>(n);
  }
  return crc;
}

// Writes rcdem's header into the user block of the finished file.
void seal(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) throw Reject{std::strerror(errno)};
  try {
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw Reject{std::strerror(errno)};
    const auto size = static_cast<std::uint64_t>(st.st_size);
    Out head;
    head.bytes(kSealMagic, 8);
    head.u32(1);  // the header's version
    head.u32(0);  // its CRC-32, set below over what follows it
    head.u64(size);
    const std::string note = "\nrcdem checkpoint: HDF5 from byte 512 (docs/checkpoint.md)\n";
    head.bytes(note.data(), note.size());
    head.buf.resize(kSealBytes, '\0');
    if (::pwrite(fd, head.buf.data(), head.buf.size(), 0) != static_cast<ssize_t>(kSealBytes))
      throw Reject{std::strerror(errno)};
    head.put_u32_at(12, crc_of(fd, kSealCovered, size));
    if (::pwrite(fd, head.buf.data() + 12, 4, 12) != 4) throw Reject{std::strerror(errno)};
    ::close(fd);
  } catch (...) {
    ::close(fd);
    throw;
  }
}

}  // namespace

void check_seal(int fd, std::uint64_t size) {
  unsigned char head[24];
  if (size < kSealBytes || ::pread(fd, head, sizeof head, 0) != static_cast<ssize_t>(sizeof head))
    throw Reject{
        fmt::format("truncated: {} bytes, shorter than its header ({})", size, kSealBytes)};
  const std::uint32_t version = load_le32(head + 8), stored = load_le32(head + 12);
  const std::uint64_t written = load_le64(head + 16);
  if (version != 1)
    throw Reject{
        fmt::format("rcdem's HDF5 header version {} is not one this rcdem reads (1)", version)};
  if (size < written) throw Reject{fmt::format("truncated: {} of {} bytes", size, written)};
  if (size > written)
    throw Reject{
        fmt::format("{} bytes where its header says {}: data after the end", size, written)};
  const std::uint32_t computed = crc_of(fd, kSealCovered, size);
  if (stored != computed)
    throw Reject{fmt::format(
        "checksum mismatch (stored CRC-32 {:08x}, computed {:08x}): the file is corrupted", stored,
        computed)};
}

void write_hdf5_checkpoint(const std::filesystem::path& file, const Parsed& image,
                           const std::vector<CheckpointColumn>& layout) {
  start_hdf5();
  std::map<std::string, std::vector<const CheckpointColumn*>> columns;
  for (const CheckpointColumn& c : layout) columns[c.section].push_back(&c);
  const Handle fcpl = ordered(H5P_FILE_CREATE), gcpl = ordered(H5P_GROUP_CREATE);
  H5Pset_userblock(fcpl, kSealBytes);
  Handle fapl{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
  // The 1.8 format: readable by every HDF5 since 1.8, and its metadata carries checksums.
  H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18);
  // No lock: nothing else opens the temporary file, and some cluster file systems refuse locks.
  H5Pset_file_locking(fapl, false, true);
  Handle f{must(H5Fcreate(file.c_str(), H5F_ACC_EXCL, fcpl, fapl), "cannot create it"), H5Fclose};
  write_header(f, image);
  for (const std::string& name : image.order) {
    const Section& s = image.sections.at(name);
    Handle g{must(H5Gcreate2(f, name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT),
                  fmt::format("cannot create group '{}'", name)),
             H5Gclose};
    const char* payload = image.data.data() + s.offset;
    const std::vector<const CheckpointColumn*>& cols = columns[name];
    if (s.kind == kKindWords) {
      put_text(g, "kind", "words");
      put_number(g, "width", H5T_STD_U32LE, H5T_NATIVE_UINT32, s.width);
      put_number(g, "count", H5T_STD_U64LE, H5T_NATIVE_UINT64, s.count);
      write_words(g, name, s, payload, cols);
    } else {
      write_bytes(g, name, s, payload, !cols.empty() && cols.front()->name == "text");
    }
  }
  must_succeed(f.close(), "cannot finish it");
  seal(file);
}

// ---------------------------------------------------------------------------------------------
// Reading.

namespace {

// One dataset of a section as found in the file: where its words go in a record.
struct ColumnPlan {
  std::string name;
  hsize_t offset = 0, words = 0;
  bool real = false;
};
struct SectionPlan {
  std::string name;
  std::string kind;  // "words", "text" or "bytes"
  std::uint32_t width = 0;
  std::uint64_t count = 0;
  std::vector<ColumnPlan> columns;
  std::uint64_t payload_bytes() const { return kind == "words" ? 8ULL * width * count : count; }
};

// The name of link k of `g` in the order written (rcdem's files index it).
std::string link_name(hid_t g, hsize_t k, const std::string& where) {
  const ssize_t n =
      H5Lget_name_by_idx(g, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
  if (n < 0)
    throw Reject{fmt::format(
        "malformed: {} does not keep the order its members were written in (not written by "
        "rcdem)",
        where)};
  std::string name(static_cast<std::size_t>(n) + 1, '\0');
  H5Lget_name_by_idx(g, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, k, name.data(), name.size(),
                     H5P_DEFAULT);
  name.resize(static_cast<std::size_t>(n));
  return name;
}

hsize_t member_count(hid_t g) {
  H5G_info_t info{};
  must_succeed(H5Gget_info(g, &info), "cannot list a group");
  return info.nlinks;
}

// A dataset's shape checked against its section: `count` records (rank 1, or rank 2 of
// `words` each), elements of `element_bytes`, all of them stored uncompressed in the file.
hsize_t checked_words(hid_t d, const std::string& where, std::uint64_t count,
                      std::size_t element_bytes) {
  const Handle space{H5Dget_space(d), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space);
  hsize_t dims[2] = {0, 1};
  if (rank < 1 || rank > 2 || H5Sget_simple_extent_dims(space, dims, nullptr) < 0)
    throw Reject{fmt::format("malformed: dataset '{}' is not a table", where)};
  if (dims[0] != count || dims[1] == 0)
    throw Reject{fmt::format("malformed: dataset '{}' has {} records, its section {}", where,
                             dims[0], count)};
  const Handle type{H5Dget_type(d), H5Tclose};
  if (H5Tget_size(type) != element_bytes)
    throw Reject{fmt::format("malformed: dataset '{}' has elements of {} bytes, expected {}", where,
                             H5Tget_size(type), element_bytes)};
  if (H5Dget_storage_size(d) != count * dims[1] * element_bytes)
    throw Reject{
        fmt::format("malformed: dataset '{}' is not stored whole and uncompressed", where)};
  return dims[1];
}

SectionPlan plan_section(hid_t f, const std::string& name) {
  SectionPlan s;
  s.name = name;
  const std::string where = fmt::format("group '{}'", name);
  Handle g{must(H5Gopen2(f, name.c_str(), H5P_DEFAULT), fmt::format("malformed: {}", where)),
           H5Gclose};
  s.kind = text_attribute(g, "kind", where);
  s.count = number_attribute<std::uint64_t>(g, "count", H5T_NATIVE_UINT64, where);
  if (s.kind == "text" || s.kind == "bytes") return s;
  if (s.kind != "words")
    throw Reject{fmt::format("malformed: {} has kind '{}' (words, text or bytes)", where, s.kind)};
  s.width = number_attribute<std::uint32_t>(g, "width", H5T_NATIVE_UINT32, where);
  hsize_t offset = 0;
  for (hsize_t k = 0, n = member_count(g); k < n; ++k) {
    ColumnPlan c;
    c.name = link_name(g, k, where);
    const std::string column = name + "/" + c.name;
    Handle d{must(H5Dopen2(g, c.name.c_str(), H5P_DEFAULT),
                  fmt::format("malformed: '{}' is not a dataset", column)),
             H5Dclose};
    const Handle type{H5Dget_type(d), H5Tclose};
    const H5T_class_t cls = H5Tget_class(type);
    if (cls != H5T_FLOAT && cls != H5T_INTEGER)
      throw Reject{fmt::format("malformed: dataset '{}' holds no numbers", column)};
    c.real = cls == H5T_FLOAT;
    c.words = checked_words(d, column, s.count, 8);
    c.offset = offset;
    offset += c.words;
    s.columns.push_back(std::move(c));
  }
  if ((s.count > 0 || !s.columns.empty()) && offset != s.width)
    throw Reject{fmt::format("malformed: {}'s datasets hold {} words a record, its width is {}",
                             where, offset, s.width)};
  return s;
}

void read_words(hid_t g, const SectionPlan& s, char* payload) {
  for (const ColumnPlan& c : s.columns) {
    Handle d{must(H5Dopen2(g, c.name.c_str(), H5P_DEFAULT), "cannot open a dataset"), H5Dclose};
    const Handle m = record_columns(s.count, s.width, c.offset, c.words);
    must_succeed(
        H5Dread(d, c.real ? H5T_IEEE_F64LE : H5T_STD_I64LE, m, H5S_ALL, H5P_DEFAULT, payload),
        fmt::format("cannot read dataset '{}/{}'", s.name, c.name));
  }
}

void read_bytes(hid_t g, const SectionPlan& s, char* payload) {
  const std::string where = s.name + "/" + s.kind;
  Handle d{must(H5Dopen2(g, s.kind.c_str(), H5P_DEFAULT),
                fmt::format("malformed: dataset '{}' is missing", where)),
           H5Dclose};
  if (s.kind == "bytes") {
    checked_words(d, where, s.count, 1);
    if (s.count > 0)
      must_succeed(H5Dread(d, H5T_STD_U8LE, H5S_ALL, H5S_ALL, H5P_DEFAULT, payload),
                   fmt::format("cannot read dataset '{}'", where));
    return;
  }
  const Handle type{H5Dget_type(d), H5Tclose};
  const Handle space{H5Dget_space(d), H5Sclose};
  if (H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) <= 0 ||
      H5Sget_simple_extent_type(space) != H5S_SCALAR)
    throw Reject{fmt::format("malformed: dataset '{}' is not one text", where)};
  const Handle t = text_type();
  char* p = nullptr;
  must_succeed(H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, &p),
               fmt::format("cannot read dataset '{}'", where));
  const std::size_t n = p ? std::strlen(p) : 0;
  if (n == s.count && n > 0) std::memcpy(payload, p, n);
  H5Dvlen_reclaim(t, space, H5P_DEFAULT, &p);
  if (n != s.count)
    throw Reject{
        fmt::format("malformed: text '{}' has {} bytes, its section {}", where, n, s.count)};
}

CheckpointHeader read_header(hid_t f, std::uint32_t& crc) {
  const std::string where = "the file";
  if (H5Aexists(f, "format") <= 0 || text_attribute(f, "format", where) != kFormatName)
    throw Reject{
        fmt::format("an HDF5 file, but not an rcdem checkpoint (its attribute 'format' "
                    "is not '{}')",
                    kFormatName)};
  CheckpointHeader h;
  h.version = number_attribute<std::uint32_t>(f, "version", H5T_NATIVE_UINT32, where);
  h.step = number_attribute<std::int64_t>(f, "step", H5T_NATIVE_INT64, where);
  h.time = number_attribute<double>(f, "time", H5T_NATIVE_DOUBLE, where);
  h.scenario_hash = number_attribute<std::uint64_t>(f, "scenario_hash", H5T_NATIVE_UINT64, where);
  h.specimen_fingerprint =
      number_attribute<std::uint64_t>(f, "specimen_fingerprint", H5T_NATIVE_UINT64, where);
  h.writer = text_attribute(f, "writer", where);
  crc = number_attribute<std::uint32_t>(f, "crc32", H5T_NATIVE_UINT32, where);
  return h;
}

}  // namespace

std::string read_hdf5_checkpoint(const std::filesystem::path& file, std::uint64_t file_size) {
  start_hdf5();
  Handle fapl{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
  // Only reads: no lock needed (the run directory has its own), and some cluster file systems
  // refuse locks.
  H5Pset_file_locking(fapl, false, true);
  const hid_t opened = H5Fopen(file.c_str(), H5F_ACC_RDONLY, fapl);
  if (opened < 0) throw Reject{open_failure()};
  Handle f{opened, H5Fclose};
  std::uint32_t crc = 0;
  CheckpointHeader h = read_header(f, crc);
  std::vector<SectionPlan> plan;
  std::uint64_t payload = 0;
  for (hsize_t k = 0, n = member_count(f); k < n; ++k) {
    plan.push_back(plan_section(f, link_name(f, k, "the file")));
    payload += plan.back().payload_bytes();
    if (payload > file_size)  // data shared between datasets, or not in the file at all
      throw Reject{fmt::format("malformed: its sections hold more than its {} bytes", file_size)};
  }
  h.sections = static_cast<std::uint32_t>(plan.size());
  Out image;
  image.buf = image_header(h);
  std::uint64_t size = image.buf.size() + payload + kImageTrailer;
  for (const SectionPlan& s : plan) size += 4 + s.name.size() + 16;
  image.put_u64_at(kImageFileSizeAt, size);
  image.buf.reserve(static_cast<std::size_t>(size));
  for (const SectionPlan& s : plan) {
    image.u32(static_cast<std::uint32_t>(s.name.size()));
    image.bytes(s.name.data(), s.name.size());
    image.u32(s.kind == "words" ? kKindWords : kKindBytes);
    image.u32(s.kind == "words" ? s.width : 1);
    image.u64(s.count);
    const std::size_t at = image.buf.size();
    image.buf.resize(at + static_cast<std::size_t>(s.payload_bytes()));
    Handle g{H5Gopen2(f, s.name.c_str(), H5P_DEFAULT), H5Gclose};
    if (s.kind == "words")
      read_words(g, s, image.buf.data() + at);
    else
      read_bytes(g, s, image.buf.data() + at);
  }
  image.u32(crc);
  return std::move(image.buf);
}

}  // namespace rcdem::io::checkpoint_detail
