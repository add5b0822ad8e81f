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

}  // namespace rcdem
