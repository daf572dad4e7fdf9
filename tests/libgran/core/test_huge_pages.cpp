// When a gran program re-executes itself to get transparent huge pages (huge_pages.hpp), and
// with which GLIBC_TUNABLES.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "libgran/core/huge_pages.hpp"

namespace gran {
namespace {

const std::string kMadvise = "always [madvise] never";

TEST(HugePages, OnRequestOnlyTheTunableIsSetForTheReExecution) {
    EXPECT_EQ(huge_page_tunables(nullptr, nullptr, nullptr, kMadvise),
              std::optional<std::string>("glibc.malloc.hugetlb=1"));
}

TEST(HugePages, OtherTunablesAreKeptAndTheHugePageOneAppended) {
    EXPECT_EQ(huge_page_tunables(nullptr, nullptr, "glibc.malloc.arena_max=2", kMadvise),
              std::optional<std::string>("glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1"));
}

TEST(HugePages, NothingIsDoneWhenTurnedOffAlreadyDoneOrDecidedByTheUser) {
    EXPECT_FALSE(huge_page_tunables("0", nullptr, nullptr, kMadvise)) << "GRAN_HUGE_PAGES=0";
    EXPECT_FALSE(huge_page_tunables(nullptr, "1", nullptr, kMadvise)) << "re-executed already";
    EXPECT_FALSE(huge_page_tunables(nullptr, nullptr, "glibc.malloc.hugetlb=0", kMadvise))
        << "the user's own choice";
    EXPECT_TRUE(huge_page_tunables("1", nullptr, nullptr, kMadvise)) << "any value but 0: on";
}

TEST(HugePages, NothingIsDoneWhereTheKernelGivesThemToAllOrToNone) {
    EXPECT_FALSE(huge_page_tunables(nullptr, nullptr, nullptr, "[always] madvise never"));
    EXPECT_FALSE(huge_page_tunables(nullptr, nullptr, nullptr, "always madvise [never]"));
    EXPECT_FALSE(huge_page_tunables(nullptr, nullptr, nullptr, "")) << "no THP in this kernel";
}

// Calls use_huge_pages and checks that it returned without re-executing (a re-executed test
// would find GLIBC_TUNABLES and GRAN_HUGE_PAGES_SET changed).
void expect_call_returns_and_changes_no_variable() {
    const char* before = std::getenv("GLIBC_TUNABLES");
    const std::string kept = before ? before : "<unset>";
    char name[] = "gran_tests";
    char* argv[] = {name, nullptr};
    use_huge_pages(argv);
    const char* after = std::getenv("GLIBC_TUNABLES");
    EXPECT_EQ(after ? std::string(after) : "<unset>", kept);
    EXPECT_EQ(std::getenv("GRAN_HUGE_PAGES_SET"), nullptr);
}

// The no-op path of the program's call: it returns and leaves the environment as it was.
TEST(HugePages, TurnedOffTheCallReturnsAndChangesNoVariable) {
    ASSERT_EQ(setenv("GRAN_HUGE_PAGES", "0", 1), 0);
    expect_call_returns_and_changes_no_variable();
    unsetenv("GRAN_HUGE_PAGES");
}

// libgomp binds the initial thread at start-up when OMP_PROC_BIND names a binding (its first
// entry, any case) or when OMP_PLACES is set without OMP_PROC_BIND (OMP_DISPLAY_ENV shows
// OMP_PROC_BIND = 'TRUE' then); a re-execution would inherit that one place.
TEST(HugePages, OpenMPBindingIsReadAsLibgompReadsIt) {
    EXPECT_FALSE(openmp_binds_threads(nullptr, nullptr));
    EXPECT_FALSE(openmp_binds_threads("false", nullptr));
    EXPECT_FALSE(openmp_binds_threads("FALSE", "cores")) << "false wins over places";
    EXPECT_FALSE(openmp_binds_threads(" False ,close", nullptr)) << "the first entry decides";
    EXPECT_TRUE(openmp_binds_threads("true", nullptr));
    EXPECT_TRUE(openmp_binds_threads("spread", nullptr));
    EXPECT_TRUE(openmp_binds_threads("close,spread", "cores"));
    EXPECT_TRUE(openmp_binds_threads(nullptr, "cores")) << "places alone bind";
}

// With a binding the program does not re-execute: the environment stays as it was (were it to
// re-execute, the re-executed test would find GLIBC_TUNABLES and GRAN_HUGE_PAGES_SET changed).
TEST(HugePages, WithOpenMPBindingTheCallReturnsAndChangesNoVariable) {
    ASSERT_EQ(setenv("OMP_PROC_BIND", "close", 1), 0);
    expect_call_returns_and_changes_no_variable();
    unsetenv("OMP_PROC_BIND");
}

}  // namespace
}  // namespace gran
