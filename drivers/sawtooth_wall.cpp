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

const bool registered = register_plugin<Driver, SawtoothWall>(
    "sawtooth_wall",
    "sawtooth vibrating wall: particles meet the wall moving into the gas at speed v0",
    wall_schema({real("velocity", "", "velocity", "wall speed v0 (directed into the gas)", 0,
                      1e308, true)}));

}  // namespace
}  // namespace gran
