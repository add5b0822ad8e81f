#include "rcdem/core/build_info.hpp"

#include "rcdem_git_hash.hpp"  // generated in the build tree by cmake/git_hash.cmake

namespace rcdem {

const char* build_version() { return RCDEM_VERSION; }
const char* build_git_hash() { return RCDEM_GIT_HASH; }

}  // namespace rcdem
