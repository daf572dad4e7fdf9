#pragma once
// What built this program: the version, the git commit and whether the tree had changes, the
// build type. Written into every result (/provenance) and printed by `gran --version`; a study
// reuses a result only when its code_id equals this build's. Generated at build time by
// cmake/build_info.cmake (the commit is "unknown" outside a git checkout).
#include <string>

namespace gran {

struct BuildInfo {
    const char* version;     // the project's version (CMakeLists.txt)
    const char* commit;      // full hash of HEAD, or "unknown"
    bool dirty;              // the tree had uncommitted changes or untracked files
    const char* diff_hash;   // 12 hex digits of the changes' SHA-256 when dirty, else ""
    const char* build_type;  // CMAKE_BUILD_TYPE, "+asan,ubsan" when sanitized
    const char* compiler;    // compiler id and version

    // One string that differs whenever the code differs: "0.1.0+<commit 12>[.dirty.<hash>]".
    std::string code_id() const {
        std::string id = std::string(version) + "+" + std::string(commit).substr(0, 12);
        if (dirty) id += std::string(".dirty.") + diff_hash;
        return id;
    }
};

const BuildInfo& build_info();

}  // namespace gran
