#include "rcdem/core/huge_pages.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

namespace rcdem {

namespace {

constexpr const char* kHugeTlb = "glibc.malloc.hugetlb";

// The bracketed word of the kernel's THP setting ("always [madvise] never"), or empty.
std::string thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto open = s.find('['), close = s.find(']');
  if (open == std::string::npos || close == std::string::npos || close < open) return {};
  return s.substr(open + 1, close - open - 1);
}

}  // namespace

std::optional<std::string> tunables_for_huge_pages(const char* tunables,
                                                   const std::string& thp_mode,
                                                   const char* rcdem_huge_pages) {
  if (rcdem_huge_pages || thp_mode != "madvise") return std::nullopt;
  const std::string current = tunables ? tunables : "";
  if (current.find(kHugeTlb) != std::string::npos) return std::nullopt;
  return (current.empty() ? "" : current + ":") + kHugeTlb + "=1";
}

void prefer_huge_pages(char** argv) {
  const std::optional<std::string> tunables = tunables_for_huge_pages(
      std::getenv("GLIBC_TUNABLES"), thp_mode(), std::getenv("RCDEM_HUGE_PAGES"));
  if (!tunables) return;
  // Set before the start, so that a loader that drops GLIBC_TUNABLES (a set-user-ID program)
  // cannot make it start again and again.
  ::setenv("RCDEM_HUGE_PAGES", "on", 1);
  ::setenv("GLIBC_TUNABLES", tunables->c_str(), 1);
  ::execv("/proc/self/exe", argv);
  // Not started again (no /proc): the tunables are left for the programs this one starts.
}

}  // namespace rcdem
