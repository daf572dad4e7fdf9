#include "libgran/core/huge_pages.hpp"

#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <fstream>

namespace gran {

namespace {
constexpr const char* kAlreadySet = "GRAN_HUGE_PAGES_SET";  // set before the re-execution
}

std::optional<std::string> huge_page_tunables(const char* gran_huge_pages, const char* already_set,
                                              const char* glibc_tunables,
                                              const std::string& thp_modes) {
    if (gran_huge_pages && std::string(gran_huge_pages) == "0") return std::nullopt;
    if (already_set) return std::nullopt;  // this is the re-executed program
    // "always": every large mapping has them already; "never": none to be had.
    if (thp_modes.find("[madvise]") == std::string::npos) return std::nullopt;
    const std::string tunables = glibc_tunables ? glibc_tunables : "";
    if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return std::nullopt;
    return tunables.empty() ? "glibc.malloc.hugetlb=1" : tunables + ":glibc.malloc.hugetlb=1";
}

bool openmp_binds_threads(const char* omp_proc_bind, const char* omp_places) {
    if (!omp_proc_bind) return omp_places != nullptr;
    std::string first(omp_proc_bind);
    first = first.substr(0, first.find(','));
    const auto space = [](char c) { return c == ' ' || c == '\t'; };
    while (!first.empty() && space(first.front())) first.erase(first.begin());
    while (!first.empty() && space(first.back())) first.pop_back();
    for (char& c : first) c = char(std::tolower(static_cast<unsigned char>(c)));
    return first != "false";
}

void use_huge_pages(char** argv) {
    if (openmp_binds_threads(std::getenv("OMP_PROC_BIND"), std::getenv("OMP_PLACES"))) return;
    std::string modes;
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::getline(in, modes);
    const char* old = std::getenv("GLIBC_TUNABLES");
    const std::optional<std::string> wanted =
        huge_page_tunables(std::getenv("GRAN_HUGE_PAGES"), std::getenv(kAlreadySet), old, modes);
    if (!wanted) return;
    const std::string kept = old ? old : "";
    if (setenv("GLIBC_TUNABLES", wanted->c_str(), 1) == 0 && setenv(kAlreadySet, "1", 1) == 0)
        execv("/proc/self/exe", argv);
    // Not re-executed: carry on as before, without handing the tunable to child processes.
    if (old) {
        setenv("GLIBC_TUNABLES", kept.c_str(), 1);
    } else {
        unsetenv("GLIBC_TUNABLES");
    }
    unsetenv(kAlreadySet);
}

}  // namespace gran
