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

// The no-op path of the program's call: it returns and leaves the environment as it was.
TEST(HugePages, TurnedOffTheCallReturnsAndChangesNoVariable) {
    ASSERT_EQ(setenv("GRAN_HUGE_PAGES", "0", 1), 0);
    const char* before = std::getenv("GLIBC_TUNABLES");
    const std::string kept = before ? before : "<unset>";
    char name[] = "gran_tests";
    char* argv[] = {name, nullptr};
    use_huge_pages(argv);
    const char* after = std::getenv("GLIBC_TUNABLES");
    EXPECT_EQ(after ? std::string(after) : "<unset>", kept);
    EXPECT_EQ(std::getenv("GRAN_HUGE_PAGES_SET"), nullptr);
    unsetenv("GRAN_HUGE_PAGES");
}

}  // namespace
}  // namespace gran
