#pragma once
// Registry of hard-particle pair laws. A law turns its parameters into the per-pair coefficients
// the event-driven engine reads in its collision kernel (no virtual call per collision).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "libgran/core/params.hpp"
#include "species/species.hpp"

namespace gran {

struct PairLaw {
    std::string name;
    std::string summary;
    Schema schema;
    std::function<void(const Params&, PairCoefficients&)> apply;
    // Markdown paragraphs for docs/scene-reference.md (`gran list --markdown`); may be empty.
    std::string description = {};
};

// Introduction of the pair laws in docs/scene-reference.md.
inline constexpr const char* kPairLawsDescription =
    R"md(
`interactions.law` chooses the law of every pair and `interactions.pairs[].law` that of one
pair; the law's parameters are keys of the same map. Kinetic-theory estimates that need a single
restitution (e.g. the thermostat's default interval) use the law's nominal value, given with each
law below.)md";

class PairLawRegistry {
  public:
    static PairLawRegistry& instance() {
        static PairLawRegistry r;
        return r;
    }
    bool add(PairLaw law) {
        const std::string key = law.name;
        return laws_.emplace(key, std::move(law)).second;
    }
    const PairLaw* find(const std::string& name) const {
        auto it = laws_.find(name);
        return it == laws_.end() ? nullptr : &it->second;
    }
    std::vector<const PairLaw*> all() const {
        std::vector<const PairLaw*> v;
        for (const auto& [k, l] : laws_) v.push_back(&l);
        return v;
    }
    std::vector<std::string> names() const {
        std::vector<std::string> v;
        for (const auto& [k, l] : laws_) v.push_back(k);
        return v;
    }

  private:
    std::map<std::string, PairLaw> laws_;
};

}  // namespace gran
