// Static wall with normal restitution e: v_n' = -e v_n (e = 1: the default elastic wall).
#include "drivers/wall_driver.hpp"

namespace gran {
namespace {

template <int D>
class StaticWall final : public WallDriver<D> {
  public:
    StaticWall(const Params& p, const SceneInfo& info)
        : WallDriver<D>(p, info, &static_wall_rule<D>, WallParams{p.real("restitution")},
                        "static") {}
};

const bool registered = register_plugin<Driver, StaticWall>(
    "static_wall", "static wall on a bounded axis with normal restitution",
    wall_schema(
        {real("restitution", "1", "", "normal restitution against the wall", 0, 1, true, false)}));

}  // namespace
}  // namespace gran
