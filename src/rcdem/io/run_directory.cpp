#include "rcdem/io/run_directory.hpp"

#include <unistd.h>

#include "rcdem/core/error.hpp"

namespace rcdem::io {

void prepare_output_directory(const std::filesystem::path& dir, bool force) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      fail("output path '{}' exists and is not a directory", dir.string());
    if (!fs::is_empty(dir, ec) && !force)
      fail("output directory '{}' is not empty; use --force to overwrite its results",
           dir.string());
  } else {
    fs::create_directories(dir, ec);
    if (ec) fail("cannot create output directory '{}': {}", dir.string(), ec.message());
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    fail("output directory '{}' is not writable", dir.string());
}

}  // namespace rcdem::io
