// The scene reference documents every key the code declares.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "libgran/plugins/driver.hpp"
#include "libgran/plugins/law.hpp"
#include "libgran/plugins/observable.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {
namespace {

std::string read_doc() {
    std::ifstream in(std::string(GRAN_SOURCE_DIR) + "/docs/scene-reference.md");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void expect_documented(const std::string& doc, const std::string& key, const std::string& where) {
    EXPECT_NE(doc.find("`" + key + "`"), std::string::npos)
        << where << ": key `" << key << "` is not documented";
}

TEST(Docs, SceneReferenceMentionsEveryDeclaredKey) {
    const std::string doc = read_doc();
    ASSERT_FALSE(doc.empty());
    for (const auto& sec : scene_sections()) {
        for (const auto& p : sec.schema) expect_documented(doc, p.name, sec.name);
    }
    for (const auto* p : DriverRegistry::instance().all()) {
        expect_documented(doc, p->name, "drivers");
        for (const auto& s : p->schema) expect_documented(doc, s.name, p->name);
    }
    for (const auto* p : ObservableRegistry::instance().all()) {
        expect_documented(doc, p->name, "observables");
        for (const auto& s : p->schema) expect_documented(doc, s.name, p->name);
    }
    for (const auto* l : LawRegistry::instance().all()) {
        if (l->name.rfind("test_", 0) == 0) continue;  // laws the test binary registers itself
        expect_documented(doc, l->name, "laws");
        for (const auto& s : l->schema) expect_documented(doc, s.name, l->name);
    }
}

}  // namespace
}  // namespace gran
