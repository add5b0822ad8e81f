// core/huge_pages.hpp: when rcdem starts again with glibc's heap in huge pages, and with what.
#include <gtest/gtest.h>

#include "rcdem/core/huge_pages.hpp"

using rcdem::tunables_for_huge_pages;

TEST(HugePages, AddedUnderTheMadviseModeOnly) {
  EXPECT_EQ(tunables_for_huge_pages(nullptr, "madvise", nullptr), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_for_huge_pages("", "madvise", nullptr), "glibc.malloc.hugetlb=1");
  // `always`: the heap is in huge pages already; `never` or unknown: it cannot be.
  EXPECT_FALSE(tunables_for_huge_pages(nullptr, "always", nullptr));
  EXPECT_FALSE(tunables_for_huge_pages(nullptr, "never", nullptr));
  EXPECT_FALSE(tunables_for_huge_pages(nullptr, "", nullptr));
}

TEST(HugePages, TheUsersTunablesAreKept) {
  EXPECT_EQ(tunables_for_huge_pages("glibc.malloc.check=3", "madvise", nullptr),
            "glibc.malloc.check=3:glibc.malloc.hugetlb=1");
  // The user's own choice of the setting stands, whatever its value.
  EXPECT_FALSE(tunables_for_huge_pages("glibc.malloc.hugetlb=0", "madvise", nullptr));
  EXPECT_FALSE(tunables_for_huge_pages("a=1:glibc.malloc.hugetlb=2", "madvise", nullptr));
}

TEST(HugePages, StartedOnceAndNeverWhenTurnedOff) {
  // RCDEM_HUGE_PAGES is set before the start: a second call finds it and does nothing, even if
  // the loader dropped GLIBC_TUNABLES (a set-user-ID program), so the program cannot loop.
  EXPECT_FALSE(tunables_for_huge_pages(nullptr, "madvise", "on"));
  EXPECT_FALSE(tunables_for_huge_pages(nullptr, "madvise", "off"));
}
