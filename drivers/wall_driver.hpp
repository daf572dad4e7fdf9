#pragma once
// Walls as drivers: a wall rule (species/wall_rules.hpp) installed on one or both walls of a
// bounded axis, static or moving with a prescribed waveform. Shared by the static, thermal,
// sawtooth and vibrating wall plugins.
#include <fmt/format.h>

#include <array>
#include <stdexcept>
#include <string>

#include "libgran/core/random.hpp"
#include "libgran/plugins/driver.hpp"
#include "species/restitution_params.hpp"

namespace gran {

// A wall driver's description (docs/scene-reference.md): its own prose, then how the restitution
// keys combine (when it declares them), then what every wall driver shares.
inline std::string wall_description(const std::string& own, bool restitution_keys = true) {
    std::string s = own + "\n\n";
    if (restitution_keys) s += std::string(kWallRestitutionDescription) + "\n\n";
    return s +
           R"md(
A wall driver installs its particle-wall rule on one or both walls of a bounded axis
(`box.periodic` false there); walls without a wall driver are static and elastic. Walls have
infinite mass. Each wall driver reports its hits and the momentum it gave (sum of m |dv_n|, whole
run) per wall under `/drivers/<name>`; the `wall_pressure` observable measures rates, impulses and
pressure during the measurement.)md";
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
    using Rule = typename EventDrivenEngine<D>::WallRule;

    WallDriver(const Params& p, const SceneInfo& info, Rule rule, WallParams params,
               std::string what, WallMotion lower_motion = WallMotion::fixed(),
               WallMotion upper_motion = WallMotion::fixed())
        : rule_(rule),
          params_(params),
          motion_{lower_motion, upper_motion},
          what_(std::move(what)),
          rng_(make_rng(info.seed + 7919ull * (info.index + 1), Stream::Driver)),
          dem_motion_{lower_motion, upper_motion} {
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
        if (lower_) engine.set_wall(axis_, 0, rule_, params_, &rng_, motion_[0]);
        if (upper_) engine.set_wall(axis_, 1, rule_, params_, &rng_, motion_[1]);
    }

    // DEM: the same walls as soft contacts with restitution e (a constant law only: the damping
    // of a linear spring-dashpot is set from one e, Eq. A9). A rule other than the impact rule
    // (thermal wall) and the sawtooth limit (no wall position) are refused.
    std::string attach(DemEngine<D>& engine) override {
        if (rule_ != &impact_wall_rule<D>) {
            refusal_key_ = "type";
            return "a " + what_ + " wall is not available on the dem engine";
        }
        if (params_.restitution.kind != ImpactRestitution::Kind::constant) {
            refusal_key_ = "restitution_law";
            return "the dem engine takes a constant wall restitution (`restitution`); an impact-"
                   "speed law comes from the contact law itself (engine.contact_law: "
                   "hertz_mindlin)";
        }
        for (const auto& m : dem_motion_) {
            if (m.kind == WallMotion::Kind::sawtooth) {
                refusal_key_ = "waveform";
                return "the sawtooth limit (A -> 0) has no wall position; on the dem engine give "
                       "vibrating_wall `amplitude` and `frequency` (a real sawtooth, v0 = 2 A f)";
            }
        }
        try {
            if (lower_) engine.set_wall(axis_, 0, dem_motion_[0], params_.restitution.e_const);
            if (upper_) engine.set_wall(axis_, 1, dem_motion_[1], params_.restitution.e_const);
        } catch (const std::invalid_argument& e) {
            refusal_key_ = "restitution";
            return e.what();
        }
        dem_ = &engine;
        return {};
    }
    std::string dem_refusal_key() const override { return refusal_key_; }

    void write(h5::Group& g, YAML::Node& summary) const override {
        if (!engine_ && !dem_) return;
        g.attr("wall", what_);
        const auto& hits = engine_ ? engine_->wall_hits() : dem_->wall_hits();
        const auto& impulse = engine_ ? engine_->wall_impulse() : dem_->wall_impulse();
        for (int side = 0; side < 2; ++side) {
            if (side == 0 ? !lower_ : !upper_) continue;
            const std::string name = side == 0 ? "lower" : "upper";
            const auto code = std::size_t(2 * axis_ + side);
            g.write_scalar("hits_" + name, static_cast<std::int64_t>(hits[code]));
            summary["hits_" + name] = hits[code];
            // Whole run (equilibration included); the wall_pressure observable measures rates.
            g.write_scalar("impulse_" + name, impulse[code]);
            g.attr_on("impulse_" + name, "unit", "mass velocity");
        }
    }

  private:
    Rule rule_;
    WallParams params_;
    std::array<WallMotion, 2> motion_;  // lower, upper
    std::string what_;
    Rng rng_;
    std::string refusal_key_ = "type";

  protected:
    // The motion on the dem engine where it differs (a real sawtooth for the sawtooth limit).
    std::array<WallMotion, 2> dem_motion_;
    int axis_ = 0;
    bool lower_ = true, upper_ = true;
    const EventDrivenEngine<D>* engine_ = nullptr;
    const DemEngine<D>* dem_ = nullptr;
};

}  // namespace gran
