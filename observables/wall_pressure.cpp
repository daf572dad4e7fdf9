// Momentum transfer to the walls of one axis (McNamara & Falcon 2005, Sec. III B): per wall the
// collision frequency Nc (hits per unit time), the mean impulse per hit dI, and the time-averaged
// pressure P = Nc dI / A (Eq. 2; A the wall's area: its length in 2D, so P is a force per length).
// By momentum balance the mean pressure on a floor equals that on the lid plus the weight per area
// N m g / A, reported alongside as a check. Rates come from the engine's per-wall hit and impulse
// counters between samples; error bars from blocking over the sample intervals.
#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "libgran/plugins/observable.hpp"

namespace gran {
namespace {

template <int D>
class WallPressure final : public Observable<D> {
  public:
    WallPressure(const Params& p, const SceneInfo& info) : table_(*info.species) {
        const std::string axis = p.str("axis");
        axis_ = axis == "x" ? 0 : (axis == "y" ? 1 : 2);
        if (axis_ >= D) p.fail("axis", fmt::format("axis {} does not exist in {}D", axis, D));
        if (info.periodic[std::size_t(axis_)])
            p.fail("axis", fmt::format("axis {} is periodic: it has no walls", axis));
        area_ = 1;
        for (int a = 0; a < D; ++a) {
            if (a != axis_) area_ *= info.box_length[std::size_t(a)];
        }
    }

    void sample(const SampleContext<D>& ctx) override {
        const auto& hits = ctx.engine.wall_hits();
        const auto& imp = ctx.engine.wall_impulse();
        if (have_last_ && ctx.measuring && ctx.time > last_time_) {
            const double dt = ctx.time - last_time_;
            for (int s = 0; s < 2; ++s) {
                const auto code = std::size_t(2 * axis_ + s);
                rate_[s].push(double(hits[code] - last_hits_[s]) / dt);
                force_[s].push((imp[code] - last_impulse_[s]) / dt);
                hits_[s].push(double(hits[code] - last_hits_[s]));
                impulse_[s].push(imp[code] - last_impulse_[s]);
            }
            if (weight_ == 0) {
                // Weight of the particles along the axis, per wall area (momentum balance check).
                double m = 0;
                for (std::size_t i = 0; i < ctx.engine.particles().size(); ++i)
                    m += table_.species[ctx.engine.particles().species[i]].mass;
                weight_ = m * std::abs(ctx.engine.gravity()[axis_]) / area_;
            }
        }
        for (int s = 0; s < 2; ++s) {
            last_hits_[s] = hits[std::size_t(2 * axis_ + s)];
            last_impulse_[s] = imp[std::size_t(2 * axis_ + s)];
        }
        last_time_ = ctx.time;
        have_last_ = true;
    }

    void write(ResultGroup& g) const override {
        g.attr("area", area_);
        g.attr("definition",
               "P = Nc dI / A (McNamara & Falcon 2005, Eq. 2); dI = sum of m |dv_n| / hits");
        for (int s = 0; s < 2; ++s) {
            if (rate_[s].size() < 2) continue;
            ResultGroup w = g.group(s == 0 ? "lower" : "upper");
            w.estimate("collision_frequency", rate_[s].estimate(), "1/time");
            std::vector<double> pressure(force_[s].values().begin(), force_[s].values().end());
            for (double& x : pressure) x /= area_;
            w.estimate("pressure", block_average(pressure), D == 2 ? "force/length" : "force/area");
            bool any = false;
            for (double h : hits_[s].values()) any = any || h > 0;
            if (any) {
                w.estimate("mean_impulse", ratio_of_means(impulse_[s].values(), hits_[s].values()),
                           "mass velocity");
            }
        }
        if (weight_ > 0) g.value("weight_per_area", weight_);
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("wall_pressure");
        ar.io(weight_);
        ar.io(have_last_);
        ar.io(last_time_);
        ar.io(last_hits_);
        ar.io(last_impulse_);
        ar.io(rate_);
        ar.io(force_);
        ar.io(hits_);
        ar.io(impulse_);
    }

  private:
    const SpeciesTable& table_;
    int axis_ = 1;
    double area_ = 1;
    double weight_ = 0;
    bool have_last_ = false;
    double last_time_ = 0;
    std::array<std::uint64_t, 2> last_hits_{};
    std::array<double, 2> last_impulse_{};
    std::array<Series, 2> rate_, force_, hits_, impulse_;
};

const bool registered = register_plugin<Observable, WallPressure>(
    "wall_pressure",
    "per wall of an axis: collision frequency Nc, mean impulse per hit dI and pressure P = Nc dI / "
    "A (McNamara & Falcon 2005, Eq. 2), time-averaged over the measurement",
    {choice("axis", "", {"x", "y", "z"}, "wall normal (a bounded axis)")});

}  // namespace
}  // namespace gran
