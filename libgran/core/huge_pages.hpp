#pragma once
// Transparent huge pages for the particle arrays. Above about 10^5 particles every stage of
// both engines streams or jumps through arrays of many megabytes, and with 4 KiB pages most of
// those accesses also miss the TLB (in a virtual machine a miss walks two page tables). Where
// the kernel gives huge pages only to memory that asks for them (THP mode "madvise", the
// default of Debian's kernels), glibc's malloc asks for them when the tunable
// glibc.malloc.hugetlb=1 is set; glibc reads its tunables only at start-up, so the program sets
// the tunable and re-executes itself, once, in the same process (same pid, arguments and
// environment otherwise). Measured in docs/performance.md ("Huge pages"); no result changes.
//
// GRAN_HUGE_PAGES=0 in the environment turns this off; a GLIBC_TUNABLES that already names
// glibc.malloc.hugetlb is left as it is. Nor does the program re-execute when the OpenMP runtime
// binds threads (openmp_binds_threads): libgomp binds the initial thread to the first place
// before main() runs, the re-executed program would inherit that one place as its whole
// affinity, and every thread would then share one core (measured: a DEM run on two threads
// 2.4x slower, docs/performance.md). Set GLIBC_TUNABLES=glibc.malloc.hugetlb=1 yourself to
// have both.
#include <optional>
#include <string>

namespace gran {

// Whether the OpenMP runtime binds threads to places from start-up, from the environment (null:
// unset): OMP_PROC_BIND set to anything but false (its first entry), or OMP_PLACES set with
// OMP_PROC_BIND unset (libgomp then binds as for true).
bool openmp_binds_threads(const char* omp_proc_bind, const char* omp_places);

// Call first thing in main(). Returns when nothing is to be done or the re-execution failed
// (the program then runs with the pages it has); otherwise does not return.
void use_huge_pages(char** argv);

// The decision, from the environment (null: unset) and the kernel's THP modes
// (/sys/kernel/mm/transparent_hugepage/enabled, e.g. "always [madvise] never"): the value
// GLIBC_TUNABLES should have in the re-executed program, or nothing if it is not to re-execute.
std::optional<std::string> huge_page_tunables(const char* gran_huge_pages, const char* already_set,
                                              const char* glibc_tunables,
                                              const std::string& thp_modes);

}  // namespace gran
