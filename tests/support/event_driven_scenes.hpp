#pragma once
// Shared pieces of the event-driven engine tests that compare two runs collision by collision
// (neighbour shells against cells, a kick horizon against none): the log of the collisions, a
// bidisperse species table and a random start with Maxwellian velocities.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "libgran/core/collision_record.hpp"
#include "libgran/core/random.hpp"
#include "libgran/scene/placement.hpp"
#include "tests/support/contacts.hpp"

namespace gran::testing {

// The collisions an engine meets, in order: original ids and times.
template <int D>
class CollisionLog final : public CollisionSink<D> {
  public:
    void on_collision(const CollisionRecord<D>& c) override {
        pairs.emplace_back(std::min(c.i, c.j), std::max(c.i, c.j));
        times.push_back(c.time);
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::vector<double> times;
};

// Two species: "big" (diameter 1, mass 1) and "small" (mass 0.5).
inline SpeciesTable bidisperse(std::size_t n_big, std::size_t n_small, double small_diameter) {
    SpeciesTable t;
    t.species.push_back(Species{"big", 1.0, 1.0, 0.4, n_big});
    t.species.push_back(Species{"small", 0.5, small_diameter, 0.4, n_small});
    return t;
}

// Random positions and Maxwellian velocities at T = 1 (angular velocities allocated when the
// contacts need them).
template <int D>
Particles<D> placed(const Box<D>& box, const SpeciesTable& t, const ContactTable& c,
                    std::uint64_t seed) {
    Rng rng = make_rng(seed, Stream::Placement);
    Particles<D> p = place_random<D>(box, t, rng);
    allocate_rotation<D>(p, c);
    maxwellian_velocities<D>(p, t, 1.0, rng);
    return p;
}

}  // namespace gran::testing
