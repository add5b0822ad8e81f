#include "rcdem/core/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace rcdem {

namespace {
bool g_quiet = false;
}

void Progress::set_quiet_default(bool quiet) { g_quiet = quiet; }
bool Progress::quiet_default() { return g_quiet; }

Progress::Progress(std::string phase, bool quiet)
    : phase_(std::move(phase)),
      quiet_(quiet || g_quiet),
      tty_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

Progress::~Progress() { done(); }

void Progress::update(double fraction) {
  if (quiet_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (elapsed < 1.0 || since < (tty_ ? 0.2 : 5.0)) return;
  last_ = now;
  shown_ = true;
  const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  fmt::print(stderr, "{}{}: {:5.1f}%  elapsed {:.1f} s  ETA {:.1f} s{}", tty_ ? "\r" : "", phase_,
             100.0 * fraction, elapsed, eta, tty_ ? "   " : "\n");
  std::fflush(stderr);
}

void Progress::done() {
  if (finished_) return;
  finished_ = true;
  if (quiet_ || !shown_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  fmt::print(stderr, "{}{}: done in {:.1f} s{}\n", tty_ ? "\r" : "", phase_, elapsed,
             tty_ ? "                    " : "");
}

}  // namespace rcdem
