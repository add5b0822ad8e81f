// core/thread_waiting.hpp: rcdem waits passively unless the user chose otherwise.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "rcdem/core/thread_waiting.hpp"

TEST(ThreadWaiting, PassiveUnlessTheUserSetAPolicy) {
  const char* before = std::getenv("OMP_WAIT_POLICY");
  const std::string saved = before ? before : "";
  ::unsetenv("OMP_WAIT_POLICY");
  rcdem::prefer_passive_thread_waiting();
  EXPECT_STREQ(std::getenv("OMP_WAIT_POLICY"), "passive");
  ::setenv("OMP_WAIT_POLICY", "active", 1);
  rcdem::prefer_passive_thread_waiting();
  EXPECT_STREQ(std::getenv("OMP_WAIT_POLICY"), "active");  // the user's choice is kept
  if (before)
    ::setenv("OMP_WAIT_POLICY", saved.c_str(), 1);
  else
    ::unsetenv("OMP_WAIT_POLICY");
}
