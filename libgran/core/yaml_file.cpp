#include "libgran/core/yaml_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "libgran/core/scene_error.hpp"

namespace gran {

namespace {}  // namespace

// The text of a readable regular file, or a SceneError naming the path and the cause.
std::string read_yaml_text(const std::string& path, const std::string& what) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st))
        throw SceneError(fmt::format("{}: cannot open the {}: no such file", path, what));
    if (fs::is_directory(st))
        throw SceneError(fmt::format("{}: is a directory; expected a {} (YAML)", path, what));
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw SceneError(
            fmt::format("{}: cannot open the {}: {}", path, what, std::strerror(errno)));
    std::stringstream ss;
    ss << in.rdbuf();
    if (in.bad())
        throw SceneError(
            fmt::format("{}: cannot read the {}: {}", path, what, std::strerror(errno)));
    return ss.str();
}

namespace {

// 1-based line of the first document marker '---' after the first document's content, for the
// message refusing a second document (0 when not found).
std::size_t second_document_line(const std::string& text) {
    std::istringstream in(text);
    bool content = false;
    std::size_t line_no = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_no;
        const bool marker = line.rfind("---", 0) == 0;
        if (marker && content) return line_no;
        const auto first = line.find_first_not_of(" \t\r");
        if (!marker && first != std::string::npos && line[first] != '#' && line.rfind("%", 0) != 0)
            content = true;
    }
    return 0;
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path, const std::string& what) {
    return parse_yaml_text(read_yaml_text(path, what), path, what);
}

YAML::Node parse_yaml_text(const std::string& text, const std::string& path,
                           const std::string& what) {
    // A second document is found by its '---' marker, not by YAML::LoadAll: yaml-cpp 0.7's
    // LoadAll loops forever on some text after a first document (found by fuzzing,
    // tests/data/fuzz_corpus/loadall_hang.yaml); YAML::Load reads the first document only.
    if (const std::size_t line = second_document_line(text)) {
        throw SceneError(fmt::format(
            "{}:{}: a second YAML document (after '---'); a {} holds exactly one, put it in "
            "its own file",
            path, line, what));
    }
    try {
        return YAML::Load(text);
    } catch (const YAML::ParserException& e) {
        throw SceneError(fmt::format("{}:{}:{}: YAML syntax error: {}", path, e.mark.line + 1,
                                     e.mark.column + 1, e.msg));
    }
}

}  // namespace gran
