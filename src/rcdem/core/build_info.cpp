#include "rcdem/core/build_info.hpp"

#include "rcdem_git_hash.hpp"  // generated in the build tree by cmake/git_hash.cmake

#ifndef RCDEM_BUILD_FLAVOUR
#define RCDEM_BUILD_FLAVOUR "unknown"
#endif

namespace rcdem {

const char* build_version() { return RCDEM_VERSION; }
const char* build_git_hash() { return RCDEM_GIT_HASH; }
const char* build_flavour() { return RCDEM_BUILD_FLAVOUR; }

}  // namespace rcdem
