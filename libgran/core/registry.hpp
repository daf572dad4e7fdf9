#pragma once
// One registry type for every kind of plugin: interaction laws, drivers, observables, placements
// and engines. A plugin is one file that declares its schema and registers itself, with a static
// initialiser, under the name YAML uses; nothing central is edited to add one. Each kind of plugin
// is an entry type deriving from PluginInfo (name, summary, schema) and adding what that kind
// provides (factories, kernels); Registry<Entry> keeps the entries of one kind by name.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "libgran/core/params.hpp"

namespace gran {

// What `gran list` and the scene reference show of a plugin, and how its section is validated.
struct PluginInfo {
    std::string name;     // the name YAML uses (`type: <name>`, `law: <name>`)
    std::string summary;  // one line
    Schema schema;        // its keys
    // What the summary and the keys' docs leave out (conventions, what is refused, what is
    // written): Markdown paragraphs printed by `gran list --markdown`; may be empty.
    std::string description = {};
};

template <class Entry>
class Registry {
  public:
    static Registry& instance() {
        static Registry r;
        return r;
    }
    // False if the name is taken (the first registration stays).
    bool add(Entry e) {
        const std::string key = e.name;
        return entries_.emplace(key, std::move(e)).second;
    }
    const Entry* find(const std::string& name) const {
        auto it = entries_.find(name);
        return it == entries_.end() ? nullptr : &it->second;
    }
    std::vector<const Entry*> all() const {
        std::vector<const Entry*> v;
        for (const auto& [k, e] : entries_) v.push_back(&e);
        return v;
    }
    std::string names() const {
        std::string s;
        for (const auto& [k, e] : entries_) s += (s.empty() ? "" : ", ") + k;
        return s;
    }

  private:
    std::map<std::string, Entry> entries_;
};

struct SceneInfo;  // what plugin factories may read about the scene
                   // (libgran/plugins/scene_info.hpp)

// A plugin whose product is a class template over the dimension (drivers, observables): one
// factory for disks (2) and one for spheres (3).
template <template <int> class Base>
struct DimensionalPlugin : PluginInfo {
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

// Registers Impl<2> and Impl<3> (each constructible from (const Params&, const SceneInfo&)) in
// Registry<DimensionalPlugin<Base>>.
template <template <int> class Base, template <int> class Impl>
bool register_plugin(std::string name, std::string summary, Schema schema,
                     std::string description = {}) {
    DimensionalPlugin<Base> p;
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
    return Registry<DimensionalPlugin<Base>>::instance().add(std::move(p));
}

}  // namespace gran
