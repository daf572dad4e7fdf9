#pragma once
// `gran list`: the scene sections, laws, engines, drivers, observables and placements with their
// keys, as plain text or as the Markdown page docs/scene-reference.md (`gran list --markdown`).
// Everything comes from the declarations (schemas, summaries, descriptions); nothing here names a
// section or plugin.
#include <string>
#include <vector>

namespace gran {

enum class ReferenceFormat { text, markdown };

// The categories `gran list` takes, in the order it prints them.
const std::vector<std::string>& reference_categories();

// One category, or all of them when `category` is empty; as Markdown, all of them make the page
// (a first line saying it is generated, the title, the introduction). Throws std::invalid_argument
// for an unknown category.
std::string scene_reference(const std::string& category, ReferenceFormat format);

}  // namespace gran
