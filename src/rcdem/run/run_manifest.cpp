#include "rcdem/run/run_manifest.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>


#include "rcdem/core/error.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/run/checkpoint.hpp"

namespace rcdem::io {

namespace fs = std::filesystem;

RunLock::RunLock(const fs::path& dir, bool on) : path_(dir / "run.lock") {
  if (!on) return;
  // The holder unlinks the file when it is done, so a lock taken on a file that has since been
  // unlinked (or replaced) guards nothing: take it again on the file now at the path.
  for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      fail("cannot write in the run directory '{}': {}", dir.string(), std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
      fail("another rcdem is running in '{}' (it holds run.lock); wait for it or stop it first",
           dir.string());
    }
    struct stat held {
    }, now{};
    if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &now) == 0 && held.st_ino == now.st_ino &&
        held.st_dev == now.st_dev)
      return;
    ::close(fd_);
    fd_ = -1;
  }
  fail("cannot lock the run directory '{}': run.lock keeps changing", dir.string());
}

RunLock::~RunLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);
}

std::string iso_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Inputs scenario_inputs(const std::string& text, const fs::path& file) {
  Inputs in;
  in.hash = fnv1a64(text);
  in.list.push_back({{"path", file.string()}, {"fnv1a64", fmt::format("{:016x}", in.hash)}});
  std::vector<std::string> includes;
  try {
    const toml::table t = toml::parse(text);
    if (const toml::node* inc = t.get("include")) {
      if (auto one = inc->value_exact<std::string>()) includes.push_back(*one);
      if (const auto* arr = inc->as_array())
        for (const auto& e : *arr)
          if (auto f = e.value_exact<std::string>()) includes.push_back(*f);
    }
  } catch (const toml::parse_error&) {
    // Parsed before, so not reached; the text's hash alone then.
  }
  for (const auto& f : includes) {
    const fs::path p = fs::path(f).is_absolute() ? fs::path(f) : file.parent_path() / f;
    const std::string body = read_text(p);
    const std::uint64_t h = fnv1a64(body);
    in.hash = fnv1a64(body, in.hash ^ 0x9e3779b97f4a7c15ULL);
    in.list.push_back(
        {{"path", p.lexically_normal().string()}, {"fnv1a64", fmt::format("{:016x}", h)}});
  }
  return in;
}

Manifest::Manifest(fs::path dir, bool on) : path_(std::move(dir) / "manifest.json"), on_(on) {}

void Manifest::load_existing() {
  if (!on_) return;
  const std::string text = read_text(path_);
  j_ = nlohmann::ordered_json::parse(text, nullptr, false);
  if (j_.is_discarded() || !j_.is_object()) {
    // The record of the run's earlier sessions is lost, not the run: kept for a reader, said.
    std::error_code ec;
    const fs::path kept = path_.string() + ".damaged";
    fs::rename(path_, kept, ec);
    fmt::print(stderr,
               "rcdem: warning: {} is damaged (not a JSON object); kept as {}, and a new manifest "
               "started for this session\n",
               path_.string(), ec ? std::string("(could not be renamed)") : kept.string());
    j_ = nlohmann::ordered_json::object();
  }
  if (!j_.contains("sessions") || !j_["sessions"].is_array())
    j_["sessions"] = nlohmann::ordered_json::array();
  for (auto& s : j_["sessions"])
    if (s.value("exit_state", "") == "running") {
      s["exit_state"] = "killed";
      s["note"] = "ended without writing its exit state (SIGKILL, crash or power loss)";
    }
}

void Manifest::write() const {
  if (on_) write_file_atomically(path_, j_.dump(2) + "\n");
}

void Manifest::write_quietly() const noexcept {
  try {
    write();
  } catch (...) {
  }
}

void remove_stale_temporaries(const fs::path& dir) {
  std::error_code ec;
  for (const fs::path& d : {dir, dir / "snapshots"})
    for (const auto& e : fs::directory_iterator(d, ec))
      if (e.path().filename().string().find(".tmp.") != std::string::npos) fs::remove(e.path(), ec);
}

}  // namespace rcdem::io
