#include "libgran/scene/scene_reference.hpp"

#include <fmt/format.h>

#include <cctype>
#include <stdexcept>

#include "libgran/plugins/driver.hpp"
#include "libgran/plugins/engine.hpp"
#include "libgran/plugins/law.hpp"
#include "libgran/plugins/observable.hpp"
#include "libgran/plugins/placement.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

namespace {

// A section or plugin as both formats print it.
struct Entry {
    std::string name;
    std::string summary;
    std::string description;
    Schema schema;
};

struct Category {
    std::string text_title;
    std::string markdown_title;
    std::string description;
    std::vector<Entry> entries;
};

template <class Items>
std::vector<Entry> entries_of(const Items& items) {
    std::vector<Entry> v;
    for (const auto* p : items) v.push_back({p->name, p->summary, p->description, p->schema});
    return v;
}

Category category(const std::string& name) {
    if (name == "scene") {
        Category c{"scene sections", "Scene sections (`gran list scene`)", "", {}};
        for (const auto& s : scene_sections())
            c.entries.push_back({s.name, s.summary, s.description, s.schema});
        return c;
    }
    if (name == "laws") {
        return {"laws (interactions.law)",
                "Interaction laws (`interactions.law`, `gran list laws`)", kLawsDescription,
                entries_of(LawRegistry::instance().all())};
    }
    if (name == "engines") {
        return {"engines (engine.type)", "Engines (`engine.type`, `gran list engines`)",
                kEnginesDescription, entries_of(EngineRegistry::instance().all())};
    }
    if (name == "drivers") {
        return {"drivers", "Drivers (`drivers:` list, `gran list drivers`)", kDriversDescription,
                entries_of(DriverRegistry::instance().all())};
    }
    if (name == "observables") {
        return {"observables", "Observables (`observables:` list, `gran list observables`)",
                kObservablesDescription, entries_of(ObservableRegistry::instance().all())};
    }
    if (name == "placements") {
        return {"placements (initial.placement)",
                "Placements (`initial.placement`, `gran list placements`)", kPlacementsDescription,
                entries_of(PlacementRegistry::instance().all())};
    }
    throw std::invalid_argument(
        "unknown category '" + name +
        "'; expected scene, laws, engines, drivers, observables or placements");
}

// Plain text, as `gran list` has always printed it.
std::string text_category(const Category& c) {
    std::string out = c.text_title + ":\n";
    for (const auto& e : c.entries) {
        out += "  " + e.name + ": " + e.summary + "\n";
        for (const auto& s : e.schema) {
            const std::string def = s.default_value.empty() ? (s.optional ? "optional" : "required")
                                                            : "default " + s.default_value;
            out += fmt::format("    {:<18} {} ({})\n", s.name, describe(s), def);
            out += fmt::format("    {:<18}   {}\n", "", s.doc);
        }
    }
    return out;
}

std::string trimmed(const std::string& s) {
    const auto b = s.find_first_not_of(" \n");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \n") - b + 1);
}

// A table cell: one line; a `|` must not end the cell, and outside `code` a `<` before a letter
// must not open an HTML tag (docs write e.g. {type: <driver>}, which a renderer would hide).
std::string cell(const std::string& s) {
    std::string out;
    bool code = false;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const char c = s[k];
        if (c == '`') code = !code;
        const bool tag = !code && c == '<' && k + 1 < s.size() &&
                         std::isalpha(static_cast<unsigned char>(s[k + 1]));
        if (c == '|' || tag) out += '\\';
        out += c == '\n' ? ' ' : c;
    }
    return out;
}

std::string type_and_range(const ParamSpec& s) {
    if (s.type == ParamType::Choice) {
        std::string t = "one of";
        for (std::size_t k = 0; k < s.choices.size(); ++k)
            t += (k ? ", `" : " `") + s.choices[k] + "`";
        return t;
    }
    ParamSpec bare = s;  // the unit has its own column
    bare.unit.clear();
    return describe(bare);
}

std::string table(const Schema& schema) {
    if (schema.empty()) return "No parameters.";
    std::string t = "| key | type and range | default | unit | meaning |\n|---|---|---|---|---|";
    for (const auto& s : schema) {
        const std::string def = !s.default_value.empty() ? "`" + s.default_value + "`"
                                : s.optional             ? "optional"
                                                         : "required";
        t += fmt::format("\n| `{}` | {} | {} | {} | {} |", cell(s.name), cell(type_and_range(s)),
                         cell(def), cell(s.unit), cell(s.doc));
    }
    return t;
}

// The summary is a fragment ("box geometry: ..."); as a paragraph it reads as a sentence.
std::string sentence(std::string s) {
    s = trimmed(s);
    if (s.empty()) return s;
    if (s[0] >= 'a' && s[0] <= 'z') s[0] = char(s[0] - 'a' + 'A');
    if (s.back() != '.') s += '.';
    return s;
}

// Blocks are Markdown paragraphs, headings or tables, separated by one blank line (descriptions
// are raw strings joined by their authors: extra blank lines are dropped).
void add(std::vector<std::string>& blocks, const std::string& block) {
    std::string b;
    for (char c : trimmed(block)) {
        if (c != '\n' || b.size() < 2 || b.substr(b.size() - 2) != "\n\n") b += c;
    }
    if (!b.empty()) blocks.push_back(b);
}

void markdown_category(std::vector<std::string>& blocks, const Category& c) {
    add(blocks, "## " + c.markdown_title);
    add(blocks, c.description);
    for (const auto& e : c.entries) {
        add(blocks, "### `" + e.name + "`");
        add(blocks, sentence(e.summary));
        add(blocks, e.description);
        add(blocks, table(e.schema));
    }
}

}  // namespace

const std::vector<std::string>& reference_categories() {
    static const std::vector<std::string> names{"scene",   "laws",        "engines",
                                                "drivers", "observables", "placements"};
    return names;
}

std::string scene_reference(const std::string& name, ReferenceFormat format) {
    const std::vector<std::string> names =
        name.empty() ? reference_categories() : std::vector<std::string>{name};
    std::vector<Category> categories;
    for (const auto& n : names) categories.push_back(category(n));
    if (format == ReferenceFormat::text) {
        std::string out;
        for (const auto& c : categories) out += text_category(c);
        return out;
    }
    std::vector<std::string> blocks;
    if (name.empty()) {
        add(blocks,
            "<!-- Generated by `make docs` (build/gran list --markdown > docs/scene-reference.md) "
            "from the declarations in the code: edit those, not this file. -->\n# Scene reference");
        add(blocks, scene_reference_introduction());
        add(blocks,
            "Each table gives a key's type and allowed range, its default (required: must be "
            "given;\noptional: may be left out, the meaning says what then), its unit (blank: "
            "dimensionless\nor a count) and its meaning.");
    }
    for (const auto& c : categories) markdown_category(blocks, c);
    std::string out;
    for (const auto& b : blocks) out += (out.empty() ? "" : "\n\n") + b;
    return out + "\n";
}

}  // namespace gran
