// Sawtooth vibrating wall (Barrat & Trizac 2002, Sec. III A): every particle meets the wall moving
// into the gas with speed v0 at its fixed position; with the grain-wall restitution e of
// `interactions` the rule is v_n' - u = -e (v_n - u), u = inward v0 (e = 1: v_n' = 2 v0 - v_n).
#include "drivers/wall_driver.hpp"

namespace gran {
namespace {

template <int D>
class SawtoothWall final : public WallDriver<D> {
  public:
    SawtoothWall(const Params& p, const SceneInfo& info)
        : WallDriver<D>(p, info, "sawtooth", WallMotion::sawtooth(p.real("velocity")),
                        WallMotion::sawtooth(p.real("velocity")), "velocity") {}
};

const char* const kDescription =
    R"md(
Barrat & Trizac 2002: every particle meets the wall moving into the gas at speed v0 at its
fixed position, so v_n' = 2 v0 - v_n at the lower wall (and -2 v0 - v_n at the upper) when e = 1
(`interactions: {walls: {alpha: 1}}` for inelastic grains between elastic walls). The limit
A -> 0 of a vibrating wall: the event-driven engine only (the dem engine needs a wall position; use
`vibrating_wall` with `waveform: sawtooth`, `amplitude` and `frequency`).)md";

const bool registered = register_plugin<Driver, SawtoothWall>(
    "sawtooth_wall",
    "sawtooth vibrating wall: particles meet the wall moving into the gas at speed v0",
    wall_schema({real("velocity", "", "velocity", "wall speed v0 (directed into the gas)", 0, 1e308,
                      true)}),
    wall_description(kDescription));

}  // namespace
}  // namespace gran
