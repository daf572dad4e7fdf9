#pragma once
// Tried and not kept (docs/performance.md, "Stochastic thermostat"; the next commit removes it).
// Thin pair lists for the re-prediction after a thermostat's kick (issue 15).
//
// After a kick every particle's next collision is looked for again, but only collisions before
// the next kick count (EventDrivenEngine::velocities_changed's horizon h). In a dense gas a
// particle moves a few hundredths of a diameter in h, so the pairs that can touch before h are
// far fewer than the candidates of the 3^D cells around a particle. The list holds every pair
// whose positions at the last build, o_i and o_j, were within R_i + R_j + skin, each pair once
// (from its lower index), with a skin of a few kicks' travel (Verlet's list):
//  - at a kick, particle i is "wide" when it could get farther than skin / 2 from o_i before h,
//    |r_i - o_i| + |v_i| h + |g| h^2 / 2 > skin / 2; the engine then times i against its whole
//    neighbourhood instead (wide particles are few: the fastest, and those that went far);
//  - every pair of two other particles not in the list then stays more than R_i + R_j apart
//    until h (each particle stays within skin / 2 of its o), so it cannot collide before h.
// The list is rebuilt (a grid of cells at least 2 R_max + skin wide, the forward half of each
// neighbourhood) when wide particles become more than 1/16 of all, or the skin wanted changes
// by more than a factor of 1.5. A collision inside the interval re-predicts its partners with
// the engine's full search, as always: the list serves only the pass right after a kick. It is a
// cache: not archived (a run does not depend on when it was built, engine_predict_all.cpp).
// Bookkeeping only: the engine computes every event time.
#include <cstdint>
#include <vector>

#include "libgran/core/box.hpp"
#include "libgran/core/vec.hpp"
#include "libgran/engines/event_driven/cell_list.hpp"

namespace gran {

template <int D>
class KickPairs {
  public:
    // The per-species contact radii the list is built with.
    struct Sizes {
        const std::uint32_t* species;
        const double* radius;
    };

    bool built() const { return built_; }
    // A build was refused (the box cannot change, so it would be again).
    bool refused() const { return refused_; }
    double skin() const { return skin_; }
    void clear() {
        built_ = false;
        origin_ = {};
        start_ = {};
        partner_ = {};
        grid_ = {};
    }
    // Every pair within R_i + R_j + skin at r, through a grid of cells at least `width` (2 R_max
    // + skin) wide. Returns false, and keeps nothing, when a periodic axis is too short for
    // the grid's half neighbourhoods (fewer than 4 cells).
    bool build(const Box<D>& box, double skin, double width, const std::vector<Vec<D>>& r,
               Sizes sizes);
    // Appends to `wide` the particles (all at the same time, at r) that could get farther than
    // skin / 2 from their position at the build within travel(i), their largest distance
    // before the next kick.
    template <class Travel>
    void find_wide(const Box<D>& box, const std::vector<Vec<D>>& r, Travel travel,
                   std::vector<std::uint32_t>& wide) const {
        const double half = 0.5 * skin_ * (1.0 - 1e-9);
        for (std::uint32_t i = 0; i < r.size(); ++i) {
            const double d = box.separation(r[i], origin_[i]).norm();
            if (d + travel(i) > half) wide.push_back(i);
        }
    }

    // The partners j > i of particle i, and how many.
    const std::uint32_t* partners(std::uint32_t i) const { return &partner_[start_[i]]; }
    std::size_t count(std::uint32_t i) const { return start_[i + 1] - start_[i]; }
    std::size_t pairs() const { return partner_.size(); }

  private:
    bool built_ = false;
    bool refused_ = false;
    double skin_ = 0;
    std::vector<Vec<D>> origin_;        // positions at the build
    std::vector<std::uint32_t> start_;  // particle i's partners: partner_[start_[i], start_[i+1])
    std::vector<std::uint32_t> partner_;
    CellList<D> grid_;  // the build's grid (kept for its storage)
};

extern template class KickPairs<2>;
extern template class KickPairs<3>;

}  // namespace gran
