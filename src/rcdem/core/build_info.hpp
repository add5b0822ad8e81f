#pragma once
// Which rcdem this is: recorded in run manifests and checkpoints, printed by --version.

namespace rcdem {

// RCDEM_VERSION, e.g. "0.1.0".
const char* build_version();
// The source tree's git hash at build time, "-dirty" appended when it had uncommitted changes;
// "unknown" outside a git checkout.
const char* build_git_hash();

}  // namespace rcdem
