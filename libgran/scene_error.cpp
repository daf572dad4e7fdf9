#include "libgran/scene_error.hpp"

#include <fmt/format.h>

namespace gran {

std::string locate(const Where& where, const YAML::Node& node) {
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
