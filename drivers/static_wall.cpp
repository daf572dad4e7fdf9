// Static wall on a bounded axis (e.g. a lid). Its contacts follow `interactions` under the
// driver's name: v_n' = -e v_n with the restitution of the grain-wall contact.
#include "drivers/wall_driver.hpp"

namespace gran {
namespace {

template <int D>
class StaticWall final : public WallDriver<D> {
  public:
    StaticWall(const Params& p, const SceneInfo& info) : WallDriver<D>(p, info, "static") {}
};

const char* const kDescription =
    R"md(
v_n' = -e v_n. With the box's upper wall on the vibration axis this is the lid of McNamara &
Falcon 2005 (its height is the box length).)md";

const bool registered = register_plugin<Driver, StaticWall>(
    "static_wall",
    "static wall on a bounded axis (e.g. a lid); its contacts follow `interactions` under the "
    "driver's name",
    wall_schema({}), wall_description(kDescription));

}  // namespace
}  // namespace gran
