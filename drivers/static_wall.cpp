// Static wall with normal restitution e: v_n' = -e v_n (e = 1: the default elastic wall), e
// constant or a function of the impact speed.
#include "drivers/wall_driver.hpp"

namespace gran {
namespace {

template <int D>
class StaticWall final : public WallDriver<D> {
  public:
    StaticWall(const Params& p, const SceneInfo& info)
        : WallDriver<D>(p, info, &impact_wall_rule<D>, make(p), "static") {}

  private:
    static WallParams make(const Params& p) {
        WallParams w;
        w.restitution = read_wall_restitution(p);
        return w;
    }
};

const char* const kDescription =
    R"md(
v_n' = -e v_n. With the box's upper wall on the vibration axis this is the lid of McNamara &
Falcon 2005 (its height is the box length).)md";

const bool registered = register_plugin<Driver, StaticWall>(
    "static_wall", "static wall on a bounded axis (e.g. a lid) with normal restitution",
    wall_schema(wall_restitution_schema()), wall_description(kDescription));

}  // namespace
}  // namespace gran
