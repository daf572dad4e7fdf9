#pragma once
// Reading a scene or study file: one YAML document from a readable regular file, or a SceneError
// that says what is wrong with the path (missing, a directory, unreadable) or the text (syntax
// error at line:column, a second document after '---').
#include <yaml-cpp/yaml.h>

#include <string>

namespace gran {

// `what` names the file's role in messages ("scene file", "study file").
YAML::Node load_yaml_file(const std::string& path, const std::string& what);
// The two halves: the file's text, and its one document (`path` names errors).
std::string read_yaml_text(const std::string& path, const std::string& what);
YAML::Node parse_yaml_text(const std::string& text, const std::string& path,
                           const std::string& what);

}  // namespace gran
