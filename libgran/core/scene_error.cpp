#include "libgran/core/scene_error.hpp"

#include <fmt/format.h>

namespace gran {

namespace {
thread_local std::vector<std::pair<std::string, std::string>> g_overrides;

const std::string* override_for(const std::string& path) {
    for (const auto& [p, assignment] : g_overrides) {
        if (path == p || path.rfind(p + ".", 0) == 0 || path.rfind(p + "[", 0) == 0)
            return &assignment;
    }
    return nullptr;
}
}  // namespace

OverrideScope::OverrideScope(std::vector<std::pair<std::string, std::string>> path_and_assignment) {
    g_overrides = std::move(path_and_assignment);
}
OverrideScope::~OverrideScope() {
    g_overrides.clear();
}

std::string locate(const Where& where, const YAML::Node& node) {
    if (const std::string* a = override_for(where.path)) return "--set '" + *a + "': " + where.path;
    std::string s = where.file;
    if (node.IsDefined() && node.Mark().line >= 0) {
        s += fmt::format(":{}:{}", node.Mark().line + 1, node.Mark().column + 1);
    }
    if (!where.path.empty()) s += ": " + where.path;
    return s;
}

void fail(const Where& where, const YAML::Node& node, const std::string& message) {
    throw SceneError(locate(where, node) + ": " + message);
}

}  // namespace gran
