// Scene files and their command-line overrides (`--set key=value`).
#include <fmt/format.h>

#include <algorithm>
#include <fstream>

#include "libgran/core/yaml_file.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : s) {
        if (c == sep) {
            parts.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    parts.push_back(cur);
    return parts;
}

}  // namespace

void apply_override(YAML::Node& root, const std::string& assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
        throw SceneError(fmt::format(
            "--set '{}': expected key=value, e.g. --set run.measurement=100", assignment));
    }
    const auto keys = split(assignment.substr(0, eq), '.');
    YAML::Node value;
    try {
        value = YAML::Load(assignment.substr(eq + 1));
    } catch (const YAML::Exception& e) {
        throw SceneError(fmt::format("--set '{}': value is not valid YAML: {}", assignment, e.msg));
    }
    // Walk with explicit node copies (yaml-cpp nodes are handles).
    std::vector<YAML::Node> chain{root};
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
        YAML::Node cur = chain.back();
        const std::string& key = keys[k];
        const bool index = !key.empty() && std::all_of(key.begin(), key.end(), ::isdigit);
        if (index) {
            const std::size_t idx = std::stoul(key);
            if (!cur.IsSequence() || idx >= cur.size()) {
                throw SceneError(fmt::format("--set '{}': '{}' is not an index of an existing list",
                                             assignment, key));
            }
            chain.push_back(cur[idx]);
        } else {
            if (cur.IsSequence()) {
                throw SceneError(fmt::format("--set '{}': '{}' is a list; use a numeric index",
                                             assignment, key));
            }
            if (!cur[key]) cur[key] = YAML::Node(YAML::NodeType::Map);
            chain.push_back(cur[key]);
        }
    }
    YAML::Node last = chain.back();
    const std::string& key = keys.back();
    if (!key.empty() && std::all_of(key.begin(), key.end(), ::isdigit) && last.IsSequence()) {
        const std::size_t idx = std::stoul(key);
        if (idx >= last.size())
            throw SceneError(fmt::format("--set '{}': index {} out of range", assignment, idx));
        last[idx] = value;
    } else {
        last[key] = value;
    }
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
    return load_scene_text(read_yaml_text(path, "scene file"), path, overrides);
}

Scene load_scene_text(const std::string& text, const std::string& path,
                      const std::vector<std::string>& overrides) {
    YAML::Node root = parse_yaml_text(text, path, "scene file");
    std::vector<std::pair<std::string, std::string>> paths;
    for (const auto& o : overrides) {
        apply_override(root, o);
        // "species.1.mass=2" -> "species[1].mass"
        std::string p;
        for (const auto& k : split(o.substr(0, o.find('=')), '.')) {
            const bool index = !k.empty() && std::all_of(k.begin(), k.end(), ::isdigit);
            p += index ? "[" + k + "]" : (p.empty() ? k : "." + k);
        }
        paths.emplace_back(p, o);
    }
    OverrideScope scope(paths);
    Scene sc = parse_scene(root, path);
    sc.source = text;
    sc.overrides = overrides;
    return sc;
}

}  // namespace gran
