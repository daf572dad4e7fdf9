#pragma once
// Walls as drivers: a wall rule (species/wall_rules.hpp) installed on one or both walls of a
// bounded axis. Shared by the static, thermal and sawtooth wall plugins.
#include <fmt/format.h>

#include <string>

#include "drivers/driver.hpp"
#include "libgran/random.hpp"

namespace gran {

inline Schema wall_schema(Schema extra) {
    Schema s{
        choice("axis", "", {"x", "y", "z"}, "wall normal: a bounded axis (box.periodic false)"),
        choice("side", "both", {"lower", "upper", "both"},
               "wall at 0 (lower), at L (upper), or both")};
    s.insert(s.end(), extra.begin(), extra.end());
    return s;
}

template <int D>
class WallDriver : public Driver<D> {
  public:
    using Rule = typename EventDrivenEngine<D>::WallRule;

    WallDriver(const Params& p, const SceneInfo& info, Rule rule, WallParams params,
               std::string what)
        : rule_(rule),
          params_(params),
          what_(std::move(what)),
          rng_(make_rng(info.seed + 7919ull * (info.index + 1), Stream::Driver)) {
        const std::string axis = p.str("axis");
        axis_ = axis == "x" ? 0 : (axis == "y" ? 1 : 2);
        if (axis_ >= D) p.fail("axis", fmt::format("axis {} does not exist in {}D", axis, D));
        if (info.periodic[std::size_t(axis_)]) {
            p.fail("axis",
                   fmt::format("axis {} is periodic; walls need a bounded axis (set box.periodic)",
                               axis));
        }
        const std::string side = p.str("side");
        lower_ = side != "upper";
        upper_ = side != "lower";
    }

    void attach(EventDrivenEngine<D>& engine) override {
        engine_ = &engine;
        if (lower_) engine.set_wall(axis_, 0, rule_, params_, &rng_);
        if (upper_) engine.set_wall(axis_, 1, rule_, params_, &rng_);
    }

    void write(h5::Group& g, YAML::Node& summary) const override {
        if (!engine_) return;
        g.attr("wall", what_);
        const auto& hits = engine_->wall_hits();
        if (lower_) {
            g.write_scalar("hits_lower", static_cast<std::int64_t>(hits[std::size_t(2 * axis_)]));
            summary["hits_lower"] = hits[std::size_t(2 * axis_)];
        }
        if (upper_) {
            g.write_scalar("hits_upper",
                           static_cast<std::int64_t>(hits[std::size_t(2 * axis_ + 1)]));
            summary["hits_upper"] = hits[std::size_t(2 * axis_ + 1)];
        }
    }

  private:
    Rule rule_;
    WallParams params_;
    std::string what_;
    Rng rng_;
    int axis_ = 0;
    bool lower_ = true, upper_ = true;
    const EventDrivenEngine<D>* engine_ = nullptr;
};

}  // namespace gran
