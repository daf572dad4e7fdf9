// A box vibrated as a whole along one axis (Bhateja, Sharma & Singh 2016, Fig. 5: a channel of
// width 43 d and height 10 d, periodic along y, shaken along x): every wall of the box moves with
// the same displacement A sin(omega t + phi) along the drive axis. The two walls normal to that
// axis move along their normal (as a vibrating wall does); the walls of the other bounded axes
// (floor and lid) slide in their own plane, which only a tangential contact force sees (a
// frictional soft contact on the dem engine; walls are smooth on the event-driven engine, where
// the slide changes nothing).
#include <fmt/format.h>

#include <array>
#include <numbers>
#include <string>
#include <vector>

#include "drivers/wall_driver.hpp"

namespace gran {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::array<const char*, 3> kAxisNames = {"x", "y", "z"};

template <int D>
class VibratingBox final : public Driver<D> {
  public:
    VibratingBox(const Params& p, const SceneInfo& info)
        : partner_(p.has("name") ? p.str("name") : p.str("type")),
          amplitude_(p.real("amplitude")),
          omega_(2 * kPi * p.real("frequency")),
          // Every wall the same sinusoid; phase 0: the box at its lowest coordinate along the
          // axis at t = 0 (the lower wall at 0), as a vibrating wall's `phase` 0.
          motion_(WallMotion::sinusoid(amplitude_, omega_, p.real("phase") - kPi / 2)) {
        const std::string axis = p.str("axis");
        axis_ = axis == "x" ? 0 : (axis == "y" ? 1 : 2);
        if (axis_ >= D) p.fail("axis", fmt::format("axis {} does not exist in {}D", axis, D));
        if (!(amplitude_ * omega_ > 0))
            p.fail("amplitude", "a vibrating box needs amplitude > 0 and frequency > 0");
        for (int a = 0; a < D; ++a) {
            if (info.periodic[std::size_t(a)]) continue;
            for (int side = 0; side < 2; ++side) {
                WallSpec<D> w{partner_,    a,       side, WallMotion::fixed(),
                              "amplitude", nullptr, -1,   WallMotion::fixed()};
                if (a == axis_) {
                    w.motion = motion_;
                } else {
                    w.slide_axis = axis_;
                    w.slide = motion_;
                }
                walls_.push_back(w);
            }
        }
        if (walls_.empty())
            p.fail("type", "a vibrating box needs walls: set box.periodic false on some axis");
        if (!info.periodic[std::size_t(axis_)]) {
            // The box's walls on the drive axis sweep 2 A each inside [0, L].
            const double length = info.box_length[std::size_t(axis_)];
            if (2 * amplitude_ + info.species->max_diameter() >= length) {
                p.fail("amplitude",
                       fmt::format("the box sweeps {:.4g} of the {:.4g}-long axis {} and leaves no "
                                   "room for particles",
                                   2 * amplitude_, length, axis));
            }
        }
    }

    std::vector<WallSpec<D>> walls() override { return walls_; }
    void observe(const EngineView<D>& view) override { view_ = &view; }
    void checkpoint(StateArchive& ar) override { ar.section("vibrating box " + partner_); }
    double peak_velocity() const override { return amplitude_ * omega_; }
    double drive_period() const override { return 2 * kPi / omega_; }

    void write(ResultGroup& g) const override {
        g.attr("axis", std::string(kAxisNames[std::size_t(axis_)]));
        g.value("peak_velocity", peak_velocity());
        g.file_only().value("frequency", omega_ / (2 * kPi));
        g.file_only().value("amplitude", amplitude_);
        if (!view_) return;
        const auto& hits = view_->wall_hits();
        const auto& impulse = view_->wall_impulse();
        for (const WallSpec<D>& w : walls_) {
            const auto code = std::size_t(2 * w.axis + w.side);
            const std::string name = fmt::format("{}_{}", kAxisNames[std::size_t(w.axis)],
                                                 w.side == 0 ? "lower" : "upper");
            g.value("hits_" + name, hits[code]);
            g.file_only().value("impulse_" + name, impulse[code], "mass velocity");
        }
    }

  private:
    std::string partner_;
    double amplitude_, omega_;
    WallMotion motion_;
    int axis_ = 0;
    std::vector<WallSpec<D>> walls_;
    const EngineView<D>* view_ = nullptr;
};

const char* const kDescription =
    R"md(
The whole box moves as one rigid body along `axis` with displacement A sin(2 pi f t + phi)
(Bhateja, Sharma & Singh 2016, Fig. 5: a horizontally shaken channel whose side walls and lid move
with the drive). It claims every wall of every bounded axis (no other wall driver can be given):

- the two walls normal to `axis` move along their normal, both with the same displacement (so the
  box keeps its inner width; `box.lengths` along `axis` must hold the width plus 2 A: at t = 0
  with `phase` 0 the lower wall is at 0 and the upper one at L - 2 A);
- the walls of the other bounded axes (floor, lid) stay in place along their normal and slide in
  their own plane with the same velocity A omega cos(2 pi f t + phi).

The slide enters a contact only through the tangential relative velocity: on the dem engine a
frictional law (`friction` > 0) drags the grains along; smooth contacts, and every wall contact of
the event-driven engine (whose wall hits change only the normal velocity), do not feel it. `axis`
may be periodic: then only the floor and lid move (a box of walls sliding under a periodic gas).
Its peak velocity V_p = A omega and period 1/f are those of the drive (`local_temperature` uses
them for phase bins and scaling). Reports hits and momentum given per wall (`hits_x_lower`, ...).)md";

const bool registered = register_plugin<Driver, VibratingBox>(
    "vibrating_box",
    "the whole box (every wall, floor and lid) vibrated sinusoidally along one axis: walls "
    "normal to it move along their normal, the others slide in their plane",
    {choice("axis", "", {"x", "y", "z"}, "axis of the vibration"),
     real("amplitude", "", "length", "A of A sin(2 pi f t + phi)", 0, 1e308, true),
     real("frequency", "", "1/time", "vibration frequency f", 0, 1e308, true),
     real("phase", "0", "rad", "phi; 0: the box at its lowest coordinate along the axis at t = 0",
          -1e308, 1e308)},
    kDescription);

}  // namespace
}  // namespace gran
