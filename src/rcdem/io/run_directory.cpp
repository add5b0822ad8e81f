#include "rcdem/io/run_directory.hpp"

#include <unistd.h>

#include "rcdem/core/error.hpp"

namespace rcdem::io {

bool prepare_output_directory(const std::filesystem::path& dir, bool force) {
  namespace fs = std::filesystem;
  std::error_code ec;
  bool created = false;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      fail("output path '{}' exists and is not a directory", dir.string());
    if (!fs::is_empty(dir, ec) && !force)
      fail("output directory '{}' is not empty; use --force to overwrite its results",
           dir.string());
  } else {
    fs::create_directories(dir, ec);
    if (ec) fail("cannot create output directory '{}': {}", dir.string(), ec.message());
    created = true;
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    fail("output directory '{}' is not writable", dir.string());
  return created;
}

void remove_if_created_and_empty(const std::filesystem::path& dir, bool created) noexcept {
  std::error_code ec;
  if (created && std::filesystem::is_empty(dir, ec)) std::filesystem::remove(dir, ec);
}

}  // namespace rcdem::io
