#pragma once
// Name-keyed plugin registries. A plugin is one file that declares its schema and registers itself
// under the name YAML uses; nothing central is edited to add one. Products are templated on the
// dimension, so every plugin provides a factory for disks (2) and spheres (3).
#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "libgran/core/params.hpp"

namespace gran {

struct SceneInfo;  // what factories may read about the scene (species, box, dimension)

template <template <int> class Base>
struct Plugin {
    std::string name;
    std::string summary;
    Schema schema;
    std::string description;  // Markdown paragraphs for docs/scene-reference.md; may be empty
    std::function<std::unique_ptr<Base<2>>(const Params&, const SceneInfo&)> make2;
    std::function<std::unique_ptr<Base<3>>(const Params&, const SceneInfo&)> make3;

    template <int D>
    std::unique_ptr<Base<D>> make(const Params& p, const SceneInfo& s) const {
        if constexpr (D == 2) {
            return make2(p, s);
        } else {
            return make3(p, s);
        }
    }
};

template <template <int> class Base>
class Registry {
  public:
    static Registry& instance() {
        static Registry r;
        return r;
    }
    bool add(Plugin<Base> p) {
        const std::string key = p.name;
        return plugins_.emplace(key, std::move(p)).second;
    }
    const Plugin<Base>* find(const std::string& name) const {
        auto it = plugins_.find(name);
        return it == plugins_.end() ? nullptr : &it->second;
    }
    std::vector<const Plugin<Base>*> all() const {
        std::vector<const Plugin<Base>*> v;
        for (const auto& [k, p] : plugins_) v.push_back(&p);
        return v;
    }
    std::string names() const {
        std::string s;
        for (const auto& [k, p] : plugins_) s += (s.empty() ? "" : ", ") + k;
        return s;
    }

  private:
    std::map<std::string, Plugin<Base>> plugins_;
};

// Registers Impl<2> and Impl<3> (each constructible from (const Params&, const SceneInfo&)).
// `description`: what the summary and the keys' docs leave out (conventions, what is refused, what
// is written), printed by `gran list --markdown`.
template <template <int> class Base, template <int> class Impl>
bool register_plugin(std::string name, std::string summary, Schema schema,
                     std::string description = {}) {
    Plugin<Base> p;
    p.name = std::move(name);
    p.summary = std::move(summary);
    p.schema = std::move(schema);
    p.description = std::move(description);
    p.make2 = [](const Params& prm, const SceneInfo& s) -> std::unique_ptr<Base<2>> {
        return std::make_unique<Impl<2>>(prm, s);
    };
    p.make3 = [](const Params& prm, const SceneInfo& s) -> std::unique_ptr<Base<3>> {
        return std::make_unique<Impl<3>>(prm, s);
    };
    return Registry<Base>::instance().add(std::move(p));
}

}  // namespace gran
