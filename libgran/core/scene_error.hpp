#pragma once
// Errors in scene and study files: every message names file, line, column and the key path.
#include <yaml-cpp/yaml.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gran {

// Where a value sits: the file it came from and the dotted key path inside it.
struct Where {
    std::string file;  // "scene.yaml" or "--set"
    std::string path;  // e.g. "species[1].mass"; empty at the top level

    Where child(const std::string& key) const {
        return {file, path.empty() ? key : path + "." + key};
    }
    Where item(std::size_t index) const { return {file, path + "[" + std::to_string(index) + "]"}; }
};

class SceneError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// "file:line:col: path: message" (line and column 1-based; omitted when the node has no mark).
std::string locate(const Where& where, const YAML::Node& node);

// Command-line overrides in force while a scene is validated: an error at (or below) an overridden
// key names the `--set` assignment instead of a file position. Paths in Where form
// ("species[1].mass").
struct OverrideScope {
    explicit OverrideScope(std::vector<std::pair<std::string, std::string>> path_and_assignment);
    ~OverrideScope();
    OverrideScope(const OverrideScope&) = delete;
    OverrideScope& operator=(const OverrideScope&) = delete;
};
[[noreturn]] void fail(const Where& where, const YAML::Node& node, const std::string& message);

}  // namespace gran
