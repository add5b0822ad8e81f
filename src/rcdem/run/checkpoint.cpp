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
#include <utility>

#include "rcdem/core/build_info.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/run/checkpoint_archive.hpp"
#include "rcdem/run/checkpoint_hdf5.hpp"
#include "rcdem/run/crack_record.hpp"
#include "rcdem/run/run_output.hpp"
#include "rcdem/solver/simulation_archive.hpp"

namespace rcdem::io {

namespace fs = std::filesystem;
using namespace checkpoint_detail;

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

namespace {

constexpr std::uint32_t kByteOrderMark = 0x01020304U;
// magic 8, version 4, byte-order mark 4, file size 8, step 8, time 8, scenario hash 8, specimen
// fingerprint 8, section count 4, writer length 4.
constexpr std::size_t kFixedHeader = 64;
constexpr std::size_t kTrailer = kImageTrailer;

// The state, part by part, each part's sections written by its own serialize() (docs/checkpoint.md
// lists them in this order).
// Saving sees every part as const, so a serialize() cannot change what it writes.
template <class Archive>
void walk(Archive& ar, const CheckpointParts& p) {
  const auto part = [](auto& x) -> auto& {
    if constexpr (Archive::loading)
      return x;
    else
      return std::as_const(x);
  };
  Simulation::serialize(ar, part(*p.sim));
  if (p.history) History::serialize(ar, part(*p.history));
  if (p.snapshots) SnapshotWriter::serialize(ar, part(*p.snapshots));
  if (p.cracks) CrackRecord::serialize(ar, part(*p.cracks));
  if (p.loop) LoopState::serialize(ar, part(*p.loop));
}

}  // namespace

std::vector<CheckpointColumn> checkpoint_layout(const CheckpointParts& parts) {
  std::vector<CheckpointColumn> out;
  Describer d(out);
  walk(d, parts);
  return out;
}

std::uint64_t specimen_fingerprint(const Simulation& s) {
  Out o;
  const Specimen& sp = s.specimen();
  const PlateContacts& pc = s.plate_contacts();
  const auto counts = {s.bodies().size(),
                       s.concrete_count(),
                       sp.contacts.contact_count(),
                       sp.contacts.point_count(),
                       pc.size(),
                       static_cast<Index>(s.nodes().size()),
                       static_cast<Index>(s.interfaces().size()),
                       static_cast<Index>(s.pulled_bars().size())};
  for (const Index c : counts) o.u64(static_cast<std::uint64_t>(c));
  // Only where there are ties, so that the fingerprints of specimens without any are unchanged.
  if (s.ties().size() > 0) o.u64(static_cast<std::uint64_t>(s.ties().size()));
  SaveRecord r{o};
  const Bodies& b = s.bodies();
  for (Index i = 0; i < b.size(); ++i) {
    r.put(b.position0[i]);
    r.put(b.orientation0[i]);
    r.put(b.mass[i]);
    r.put(b.inertia[i]);
    r.put(b.radius[i]);
  }
  const auto network = [&](const ContactNetwork& nw) {
    o.u64(static_cast<std::uint64_t>(nw.point_count()));
    for (Index c = 0; c < nw.contact_count(); ++c) {
      r.put(nw.particle_a[c]);
      r.put(nw.particle_b[c]);
      r.put(nw.point_begin[c]);
    }
    for (Index m = 0; m < nw.point_count(); ++m) {
      r.put(nw.point_position0[m]);
      r.put(nw.constants[m].kn);
      r.put(nw.constants[m].ks);
      r.put(nw.constants[m].fn_max);
      r.put(nw.constants[m].c_max);
    }
  };
  network(sp.contacts);
  for (const auto& ic : sp.interfaces) network(ic.net);
  for (Index k = 0; k < pc.size(); ++k) {
    r.put(pc.particle[k]);
    r.put(pc.point0[k]);
    r.put(pc.constants[k].kn);
    r.put(pc.constants[k].ks);
  }
  return fnv1a64(o.buf);
}

// ---------------------------------------------------------------------------------------------
// Files.

namespace checkpoint_detail {

std::string image_header(const CheckpointHeader& h) {
  Out o;
  o.bytes(kCheckpointMagic, 8);
  o.u32(h.version);
  o.u32(kByteOrderMark);
  o.u64(h.file_size);
  o.u64(static_cast<std::uint64_t>(h.step));
  o.f64(h.time);
  o.u64(h.scenario_hash);
  o.u64(h.specimen_fingerprint);
  o.u32(h.sections);
  o.u32(static_cast<std::uint32_t>(h.writer.size()));
  o.bytes(h.writer.data(), h.writer.size());
  return std::move(o.buf);
}

}  // namespace checkpoint_detail

namespace {

// The image with its section table, as parse_image would read it back.
Parsed encode_image(const CheckpointParts& parts, std::uint64_t scenario_hash) {
  if (!parts.sim) throw std::logic_error("encode_checkpoint: no simulation");
  const Simulation& sim = *parts.sim;
  Parsed f;
  CheckpointHeader& h = f.header;
  h.version = kCheckpointVersion;
  h.step = sim.steps();
  h.time = sim.time();
  h.scenario_hash = scenario_hash;
  h.specimen_fingerprint = specimen_fingerprint(sim);
  h.writer = fmt::format("rcdem {} ({})", build_version(), build_git_hash());
  Out o;
  o.buf = image_header(h);  // its size and section count set below
  // Condensed contacts' histories as if visited (elastic_condensation.hpp): what the file holds
  // does not depend on the condensation, and a restart needs no kinematics of the last step.
  parts.sim->catch_up_condensed_points();
  Saver saver(o);
  walk(saver, parts);
  h.sections = static_cast<std::uint32_t>(saver.sections().size());
  h.file_size = o.buf.size() + kTrailer;
  o.put_u32_at(kImageSectionCountAt, h.sections);
  o.put_u64_at(kImageFileSizeAt, h.file_size);
  o.u32(crc32(o.buf.data(), o.buf.size()));
  for (const auto& [name, section] : saver.sections()) {
    f.sections.emplace(name, section);
    f.order.push_back(name);
  }
  f.data = std::move(o.buf);
  return f;
}

}  // namespace

std::string encode_checkpoint(const CheckpointParts& parts, std::uint64_t scenario_hash) {
  return encode_image(parts, scenario_hash).data;
}

namespace {

// Reads from `fd` until `size` bytes or the end; the count read.
std::size_t read_fully(int fd, char* data, std::size_t size) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Reject{fmt::format("cannot read it: {}", std::strerror(errno))};
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  return done;
}

// The file's image in the binary format, once it is known to be a regular file (a FIFO so named
// would block the resume) that starts like a checkpoint (binary, or HDF5: converted) and fits in
// memory (a huge sparse file so named would exhaust it): anything else is rejected, and the
// previous checkpoint taken.
std::string read_checked(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw Reject{fmt::format("cannot read it: {}", std::strerror(errno))};
  if (!S_ISREG(st.st_mode)) throw Reject{"not a regular file"};
  char head[24];
  const std::size_t got = read_fully(fd, head, sizeof head);
  if (got >= 8 && std::memcmp(head, kHdf5Signature, 8) == 0)
    throw Reject{"an HDF5 file, but not an rcdem checkpoint (it lacks rcdem's header)"};
  const bool hdf5 = got >= 8 && std::memcmp(head, kSealMagic, 8) == 0;
  if (got == sizeof head && !hdf5 && std::memcmp(head, kCheckpointMagic, 8) != 0)
    throw Reject{"not an rcdem checkpoint (it starts neither with 'RCDEMCKP' nor 'RCDEMHDF')"};
  const double memory =
      static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  if (memory > 0.0 && static_cast<double>(st.st_size) > 0.5 * memory)
    throw Reject{fmt::format("{} bytes, more than half of this machine's memory", st.st_size)};
  if (hdf5) {
    check_seal(fd, static_cast<std::uint64_t>(st.st_size));
    // HDF5 opens the file checked, even if another has taken its name since.
    return read_hdf5_checkpoint("/proc/self/fd/" + std::to_string(fd),
                                static_cast<std::uint64_t>(st.st_size));
  }
  std::string data;
  try {
    data.assign(std::max(static_cast<std::size_t>(st.st_size), got), '\0');
  } catch (const std::bad_alloc&) {
    throw Reject{fmt::format("{} bytes, more than can be allocated", st.st_size)};
  }
  std::memcpy(data.data(), head, got);
  data.resize(got + read_fully(fd, data.data() + got, data.size() - got));
  return data;
}

std::string read_whole(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw Reject{fmt::format("cannot open it: {}", std::strerror(errno))};
  try {
    std::string data = read_checked(fd);
    ::close(fd);
    return data;
  } catch (...) {
    ::close(fd);
    throw;
  }
}

}  // namespace

Parsed checkpoint_detail::parse_image(std::string data) {
  Parsed f;
  f.data = std::move(data);
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
  if (h.version > kCheckpointVersion || h.version < kOldestReadableCheckpointVersion)
    throw Reject{h.version > kCheckpointVersion
                     ? fmt::format("format version {} is newer than this rcdem reads ({}); "
                                   "resume it with the rcdem that wrote it",
                                   h.version, kCheckpointVersion)
                 : h.version >= 1
                     ? fmt::format("format version {} is older than this rcdem reads ({} to "
                                   "{}); resume it with the rcdem that wrote it",
                                   h.version, kOldestReadableCheckpointVersion, kCheckpointVersion)
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
    if (!f.sections.emplace(name, s).second)
      throw Reject{fmt::format("malformed: section '{}' appears twice", name)};
    f.order.push_back(name);
  }
  if (at != end) throw Reject{"malformed: bytes between the last section and the checksum"};
  return f;
}

namespace {

Parsed parse(const fs::path& file) { return parse_image(read_whole(file)); }

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

std::string checkpoint_image(const fs::path& file) {
  try {
    return parse(file).data;
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
    walk(check, parts);
    Loader apply(f, true);
    walk(apply, parts);
    return f.header;
  } catch (const Reject& r) {
    throw Error(rejected(file, r.reason));
  }
}

fs::path checkpoint_path(const fs::path& dir, std::int64_t step) {
  return dir / fmt::format("checkpoint_{:012d}.h5", step);
}

namespace {

// The step of a checkpoint's file name (checkpoint_<digits>.h5, or .rcp as written before the
// HDF5 format), or -1.
std::int64_t checkpoint_step(const std::string& name) {
  constexpr std::string_view prefix = "checkpoint_";
  if (name.rfind(prefix, 0) != 0) return -1;
  for (const std::string_view suffix : {".h5", ".rcp"}) {
    if (name.size() <= prefix.size() + suffix.size() ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.empty() || digits.size() > 18 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return -1;
    return std::stoll(digits);
  }
  return -1;
}

}  // namespace

std::vector<CheckpointFile> list_checkpoints(const fs::path& dir) {
  std::vector<CheckpointFile> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (const std::int64_t step = checkpoint_step(e.path().filename().string()); step >= 0)
      out.push_back({e.path(), step});
  // Newest first; of two files of one step (a run resumed from the binary format), the HDF5 one.
  std::sort(out.begin(), out.end(), [](const CheckpointFile& a, const CheckpointFile& b) {
    return a.step != b.step ? a.step > b.step
                            : a.path.extension() == ".h5" && b.path.extension() != ".h5";
  });
  return out;
}

namespace {

bool is_checkpoint_temporary(const std::string& name) {
  return name.rfind("checkpoint_", 0) == 0 && (name.find(".rcp.tmp.") != std::string::npos ||
                                               name.find(".h5.tmp.") != std::string::npos);
}

void sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);  // best effort: some file systems refuse it on directories
  ::close(fd);
}

// Writes the checkpoint to `tmp`, flushes it to the disk and renames it `path`; throws Reject.
void write_synced(const fs::path& path, const fs::path& tmp, const CheckpointParts& parts,
                  std::uint64_t scenario_hash) {
  std::error_code ec;
  fs::remove(tmp, ec);  // left by an earlier process of the same id
  write_hdf5_checkpoint(tmp, encode_image(parts, scenario_hash), checkpoint_layout(parts));
  const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int err = errno;
    if (fd >= 0) ::close(fd);
    throw Reject{std::strerror(err)};
  }
  ::close(fd);
  if (::rename(tmp.c_str(), path.c_str()) != 0) throw Reject{std::strerror(errno)};
}

}  // namespace

fs::path write_checkpoint(const fs::path& dir, const CheckpointParts& parts,
                          std::uint64_t scenario_hash, int keep) {
  const fs::path path = checkpoint_path(dir, parts.sim->steps());
  const fs::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
  std::error_code ec;
  try {
    write_synced(path, tmp, parts, scenario_hash);
  } catch (const Reject& r) {
    fs::remove(tmp, ec);
    fail("cannot write checkpoint '{}': {}; the earlier checkpoints are kept", path.string(),
         r.reason);
  }
  sync_directory(dir);
  // Keep the newest `keep`; drop what an interrupted write left.
  const std::vector<CheckpointFile> all = list_checkpoints(dir);
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
    fail("no checkpoint in '{}' (checkpoint_*.h5): the run stopped before its first checkpoint",
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
