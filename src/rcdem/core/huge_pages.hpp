#pragma once
// The process's heap in transparent huge pages (2 MiB), where the kernel leaves it to the program.
//
// A cracked specimen's step reads much of its memory at scattered places (held contacts' sums,
// visited points, the bodies' spins). With 4 KiB pages each such read of a step's tens of
// megabytes also misses the TLB and walks the page table: on the 2-core test machine a random
// line's latency was 175-274 ns against 160-185 ns in huge pages, and the cracked cube's and AN4
// beam's steps ran 5% faster in them (bench/RESULTS.md, "Huge pages, and the step's memory
// floor"). Debian's default THP mode is `madvise`: only
// ranges a process asks for get huge pages, and glibc's malloc asks for its heap only under
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1, which its loader reads when the program starts. So the
// CLI (and rcdem_step_bench) start again, once, first thing in main(), with that setting added:
// the same program, arguments and process. Asking afterwards (madvise and MADV_COLLAPSE on the
// heap) copies every page already touched, about half a second for a cube's 188 MB, which a short
// run does not win back. The pages change the speed only, never a result.
#include <optional>
#include <string>

namespace rcdem {

// The GLIBC_TUNABLES value to start again with, given its present value (null: unset), the
// kernel's THP mode (the bracketed word of /sys/kernel/mm/transparent_hugepage/enabled; empty if
// unknown) and RCDEM_HUGE_PAGES (null: unset): hugetlb=1 added to the user's tunables, or nothing
// when there is nothing to do: the mode is not `madvise` (`always`: the heap is in huge pages
// already; `never`: it cannot be), the user set glibc.malloc.hugetlb or RCDEM_HUGE_PAGES (`off`
// turns this off; any other value means the program has started again already).
std::optional<std::string> tunables_for_huge_pages(const char* tunables,
                                                   const std::string& thp_mode,
                                                   const char* rcdem_huge_pages);

// Call first thing in main(): starts the program again (execv of /proc/self/exe, argv as given)
// with tunables_for_huge_pages' value and RCDEM_HUGE_PAGES=on, if there is one; returns if not,
// or if the start fails (the run then goes on in 4 KiB pages).
void prefer_huge_pages(char** argv);

}  // namespace rcdem
