// Sawtooth vibrating wall (Barrat & Trizac 2002): every particle meets the wall moving into the gas
// with speed v0 at its fixed position; v_n' = 2 v0 - v_n at the lower wall (e = 1), with an
// optional wall restitution e: v_n' - u = -e (v_n - u).
#include "drivers/wall_driver.hpp"

namespace gran {
namespace {

template <int D>
class SawtoothWall final : public WallDriver<D> {
  public:
    SawtoothWall(const Params& p, const SceneInfo& info)
        : WallDriver<D>(p, info, &impact_wall_rule<D>, make(p), "sawtooth",
                        WallMotion::sawtooth(p.real("velocity")),
                        WallMotion::sawtooth(p.real("velocity"))) {}

  private:
    static WallParams make(const Params& p) {
        WallParams w;
        w.restitution = read_wall_restitution(p);
        return w;
    }
};

const char* const kDescription =
    R"md(
Barrat & Trizac 2002: every particle meets the wall moving into the gas at speed v0 at its
fixed position, so v_n' = 2 v0 - v_n at the lower wall (and -2 v0 - v_n at the upper) when e = 1.)md";

const bool registered = register_plugin<Driver, SawtoothWall>(
    "sawtooth_wall",
    "sawtooth vibrating wall: particles meet the wall moving into the gas at speed v0",
    wall_schema([] {
        Schema s{real("velocity", "", "velocity", "wall speed v0 (directed into the gas)", 0, 1e308,
                      true)};
        for (auto& r : wall_restitution_schema()) s.push_back(r);
        return s;
    }()),
    wall_description(kDescription));

}  // namespace
}  // namespace gran
