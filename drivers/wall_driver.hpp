#pragma once
// Walls as drivers: one or both walls of a bounded axis, static or moving with a prescribed
// waveform, described to the engine (libgran/plugins/wall.hpp). Their contacts with the grains
// follow `interactions` under the driver's name (its `name`, default its type); a thermal wall
// replaces the contact by its own rule. Shared by the static, thermal, sawtooth and vibrating
// wall plugins.
#include <fmt/format.h>

#include <array>
#include <string>
#include <vector>

#include "libgran/plugins/driver.hpp"

namespace gran {

// A wall driver's description (docs/scene-reference.md): its own prose, then how its contacts
// are set (when it has contacts), then what every wall driver shares.
inline std::string wall_description(const std::string& own, bool contacts = true) {
    std::string s = own + "\n\n";
    if (contacts) {
        s += R"md(
Its contacts follow `interactions` under the driver's `name` (default: its type), like the
contacts between species: e.g. `pairs: [{between: [grain, vibrating_wall], alpha: 0.9}]`, or
`walls: {...}` for every wall. A wall moving with velocity u reflects a particle by
v_n' - u = -e (v_n - u) on the event-driven engine, e the restitution of that contact's law (a
constant, or a function of the impact speed |v_n - u|); on the dem engine the wall is a soft
contact partner of infinite mass.)md";
        s += "\n\n";
    }
    return s + R"md(
A wall driver puts walls on one or both sides of a bounded axis (`box.periodic` false there); two
drivers on the same wall are refused; walls no driver claims are static (the wall partner `box`).
Walls have infinite mass. Each wall driver reports its hits and the momentum it gave (sum of
m |dv_n|, whole run) per wall under `/drivers/<name>`; the `wall_pressure` observable measures
rates, impulses and pressure during the measurement.)md";
}

inline Schema wall_schema(Schema extra, std::string default_side = "both") {
    Schema s{
        choice("axis", "", {"x", "y", "z"}, "wall normal: a bounded axis (box.periodic false)"),
        choice("side", std::move(default_side), {"lower", "upper", "both"},
               "wall at 0 (lower), at L (upper), or both")};
    s.insert(s.end(), extra.begin(), extra.end());
    return s;
}

template <int D>
class WallDriver : public Driver<D> {
  public:
    // `motion_key`: the key that chose the motion (for an engine's refusal of it).
    WallDriver(const Params& p, const SceneInfo& info, std::string what,
               WallMotion lower_motion = WallMotion::fixed(),
               WallMotion upper_motion = WallMotion::fixed(), std::string motion_key = "type")
        : motion_{lower_motion, upper_motion},
          what_(std::move(what)),
          partner_(p.has("name") ? p.str("name") : p.str("type")),
          motion_key_(std::move(motion_key)) {
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

    std::vector<WallSpec<D>> walls() override {
        std::vector<WallSpec<D>> w;
        for (int side = 0; side < 2; ++side) {
            if (side == 0 ? !lower_ : !upper_) continue;
            w.push_back({partner_, axis_, side, motion_[std::size_t(side)], motion_key_,
                         reflection_, -1, WallMotion::fixed()});
        }
        return w;
    }
    void observe(const EngineView<D>& view) override { view_ = &view; }
    // Static, vibrating and sawtooth walls have no state of their own (motions are functions of
    // time; hits and impulses are the engine's).
    void checkpoint(StateArchive& ar) override { ar.section("wall driver " + partner_); }

    void write(ResultGroup& g) const override {
        if (!view_) return;
        g.attr("wall", what_);
        const auto& hits = view_->wall_hits();
        const auto& impulse = view_->wall_impulse();
        for (int side = 0; side < 2; ++side) {
            if (side == 0 ? !lower_ : !upper_) continue;
            const std::string name = side == 0 ? "lower" : "upper";
            const auto code = std::size_t(2 * axis_ + side);
            g.value("hits_" + name, hits[code]);
            // Whole run (equilibration included); the wall_pressure observable measures rates.
            g.file_only().value("impulse_" + name, impulse[code], "mass velocity");
        }
    }

  protected:
    // A rule replacing the contact (owned by the derived driver).
    void replace_contact(WallReflection<D>* reflection) { reflection_ = reflection; }

    std::array<WallMotion, 2> motion_;  // lower, upper
    int axis_ = 0;
    bool lower_ = true, upper_ = true;

  private:
    std::string what_;
    std::string partner_;
    std::string motion_key_;
    WallReflection<D>* reflection_ = nullptr;
    const EngineView<D>* view_ = nullptr;
};

}  // namespace gran
