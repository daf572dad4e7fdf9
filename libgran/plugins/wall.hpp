#pragma once
// A wall as a driver describes it, engine-free: on which axis and side, how it moves, which
// partner it is in `interactions` (its contacts follow the scene's contact law like any grain
// pair), or, for a wall that is not a contact at all (a thermal wall), the rule that replaces the
// collision. Each engine translates the description into its own wall (the event-driven engine
// takes the limit A -> 0 of a sawtooth ramp; the DEM engine needs a wall position and refuses the
// sawtooth limit and replacing rules).
#include <string>

#include "libgran/core/vec.hpp"
#include "libgran/core/wall_motion.hpp"

namespace gran {

// A wall hit that is not a contact: the outgoing velocity is set by the wall itself (e.g. drawn at
// the wall's temperature). One virtual call per hit of such a wall, none otherwise.
template <int D>
class WallReflection {
  public:
    virtual ~WallReflection() = default;
    // v: the particle's velocity, changed in place to leave the wall; axis: the wall normal;
    // inward: +1 for a lower wall (gas above), -1 for an upper one; u: the wall's velocity along
    // the normal; mass: the particle's.
    virtual void reflect(Vec<D>& v, int axis, double inward, double u, double mass) = 0;
};

template <int D>
struct WallSpec {
    std::string partner;  // its name in `interactions` (the driver's name)
    int axis = 0;
    int side = 0;       // 0: at 0 (lower), 1: at L (upper)
    WallMotion motion;  // prescribed motion along the normal (WallMotion::fixed(): static)
    std::string motion_key = "type";          // the driver key that chose the motion (messages)
    WallReflection<D>* reflection = nullptr;  // null: a contact with the law of `interactions`
    // Motion of the surface in its own plane, along `slide_axis` (-1: none): the floor and lid of
    // a box vibrated as a whole. It enters a contact through the tangential relative velocity
    // only, so it changes nothing for smooth walls (every wall on the event-driven engine).
    int slide_axis = -1;
    WallMotion slide;
};

}  // namespace gran
