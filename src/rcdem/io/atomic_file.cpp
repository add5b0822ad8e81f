#include "rcdem/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "rcdem/core/error.hpp"

namespace rcdem::io {

int try_write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  const auto abandon = [&](int err) {
    ::unlink(tmp.c_str());
    return err;
  };
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      return abandon(err);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    return abandon(err);
  }
  if (::close(fd) != 0) return abandon(errno);
  if (::rename(tmp.c_str(), path.c_str()) != 0) return abandon(errno);
  return 0;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  if (const int err = try_write_file_atomically(path, content))
    fail("cannot write '{}': {}", path.string(), std::strerror(err));
}

}  // namespace rcdem::io
