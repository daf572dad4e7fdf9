// docs/scene-reference.md is the output of `gran list --markdown`, and that output documents every
// declared key and description under the heading of its section or plugin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "libgran/plugins/driver.hpp"
#include "libgran/plugins/engine.hpp"
#include "libgran/plugins/law.hpp"
#include "libgran/plugins/observable.hpp"
#include "libgran/plugins/placement.hpp"
#include "libgran/scene/scene.hpp"
#include "libgran/scene/scene_reference.hpp"
#include "tests/support/run_gran.hpp"

namespace gran {
namespace {

std::string read_doc() {
    std::ifstream in(std::string(GRAN_SOURCE_DIR) + "/docs/scene-reference.md");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The first line where the committed page and the program's output differ, for the message.
std::string first_difference(const std::string& committed, const std::string& generated) {
    std::istringstream a(committed), b(generated);
    std::string la, lb;
    for (int line = 1;; ++line) {
        const bool more_a = bool(std::getline(a, la)), more_b = bool(std::getline(b, lb));
        if (!more_a && !more_b) return "";
        if (more_a != more_b || la != lb) {
            return "first difference at line " + std::to_string(line) +
                   ":\n  committed: " + (more_a ? la : "<end of file>") +
                   "\n  generated: " + (more_b ? lb : "<end>");
        }
    }
}

TEST(Docs, SceneReferenceIsUpToDate) {
    const testing::Outcome o = testing::run_gran({"list", "--markdown"});
    ASSERT_FALSE(o.signaled) << o.output;
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const std::string doc = read_doc();
    EXPECT_TRUE(o.output == doc)
        << "docs/scene-reference.md is stale: regenerate it with `make docs` (build/gran list "
           "--markdown > docs/scene-reference.md) and commit it.\n"
        << first_difference(doc, o.output);
}

struct Documented {
    std::string name;
    std::string description;
    Schema schema;
};

std::vector<Documented> in_page_order() {
    std::vector<Documented> v;
    for (const auto& s : scene_sections()) v.push_back({s.name, s.description, s.schema});
    const auto add = [&v](const auto& plugins) {
        for (const auto* p : plugins) v.push_back({p->name, p->description, p->schema});
    };
    add(LawRegistry::instance().all());
    add(EngineRegistry::instance().all());
    add(DriverRegistry::instance().all());
    add(ObservableRegistry::instance().all());
    add(PlacementRegistry::instance().all());
    return v;
}

// Every section and plugin has its heading, in the order of the declarations; below it (before
// the next heading) come its description and one table row per key.
TEST(Docs, MarkdownGivesEveryKeyARowUnderItsHeading) {
    const std::string md = scene_reference("", ReferenceFormat::markdown);
    std::size_t at = 0;
    for (const auto& d : in_page_order()) {
        const std::size_t h = md.find("\n### `" + d.name + "`\n", at);
        ASSERT_NE(h, std::string::npos) << "no heading for " << d.name << " after offset " << at;
        const std::size_t end = std::min(md.find("\n#", h + 1), md.size());
        const std::string part = md.substr(h, end - h);
        std::istringstream description(d.description);
        std::string line;
        while (line.empty() && std::getline(description, line)) {
        }
        EXPECT_NE(part.find(line), std::string::npos) << d.name << ": no description " << line;
        for (const auto& s : d.schema) {
            EXPECT_NE(part.find("\n| `" + s.name + "` | "), std::string::npos)
                << d.name << ": no row for key " << s.name;
        }
        if (d.schema.empty()) {
            EXPECT_NE(part.find("No parameters."), std::string::npos) << d.name;
        }
        at = h + 1;
    }
}

// Five cells per row whatever the docs contain (|v_n - u| must not split a cell), and no HTML tag
// outside code ({type: <driver>, ...} would be hidden by a renderer).
TEST(Docs, MarkdownTableRowsHaveFiveCellsAndNoTags) {
    std::istringstream md(scene_reference("", ReferenceFormat::markdown));
    int rows = 0;
    for (std::string line; std::getline(md, line);) {
        if (line.empty() || line[0] != '|') continue;
        int bars = 0;
        bool code = false;
        for (std::size_t k = 0; k < line.size(); ++k) {
            const bool escaped = k > 0 && line[k - 1] == '\\';
            code = code != (line[k] == '`');
            bars += line[k] == '|' && !escaped;
            EXPECT_FALSE(!code && !escaped && line[k] == '<' && k + 1 < line.size() &&
                         std::isalpha(static_cast<unsigned char>(line[k + 1])))
                << "an HTML tag at column " << k << ": " << line;
        }
        EXPECT_EQ(bars, 6) << line;
        ++rows;
    }
    EXPECT_GT(rows, 100);
}

// `gran list <category> --markdown` is that category's part of the page, and only that.
TEST(Docs, MarkdownOfOneCategoryIsItsPartOfThePage) {
    const std::string page = scene_reference("", ReferenceFormat::markdown);
    for (const auto& c : reference_categories()) {
        const std::string part = scene_reference(c, ReferenceFormat::markdown);
        EXPECT_EQ(part.rfind("## ", 0), 0u) << c << ":\n" << part.substr(0, 200);
        EXPECT_EQ(part.find("\n## "), std::string::npos) << c << ": more than one category";
        // The page separates the categories by a blank line; the part ends with one newline.
        EXPECT_NE(page.find(part.substr(0, part.size() - 1)), std::string::npos) << c;
    }
    EXPECT_THROW(scene_reference("bogus", ReferenceFormat::markdown), std::invalid_argument);
}

}  // namespace
}  // namespace gran
