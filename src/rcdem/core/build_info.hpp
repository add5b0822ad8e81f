#pragma once
// Which rcdem this is: recorded in run manifests, summaries and checkpoints, printed by --version.

namespace rcdem {

// RCDEM_VERSION, e.g. "0.1.0".
const char* build_version();
// The source tree's git hash at build time, "-dirty" appended when it had uncommitted changes;
// "unknown" outside a git checkout.
const char* build_git_hash();
// How the arithmetic was compiled: "portable Release GNU 12.2.0" (the x86-64 baseline, no
// contraction: the reference for tests/golden/) or "native ..." (-march=native).
const char* build_flavour();

}  // namespace rcdem
