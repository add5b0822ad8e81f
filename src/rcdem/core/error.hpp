#pragma once
// One exception type for every user-facing failure: its message is printed as-is, on one line,
// by the CLI, which then exits non-zero. Programming errors stay asserts.
#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace rcdem {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

// Rethrows `e` with "file: " in front, unless its message names the file already: a failure deep
// in the model's set-up (a plate that touches nothing, a cell the tessellation cannot form) still
// says which scenario caused it.
[[noreturn]] inline void rethrow_naming(const std::string& file, const Error& e) {
  const std::string message = e.what();
  if (file.empty() || message.find(file) != std::string::npos) throw e;
  throw Error(file + ": " + message);
}

}  // namespace rcdem
