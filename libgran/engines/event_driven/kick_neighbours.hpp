#pragma once
// Tried and not kept (docs/performance.md, "Stochastic thermostat"; the next commits replace and
// then remove it): thin neighbour lists for the re-prediction after a thermostat's kick.
// The pairs whose shell centres are within R_i + R_j + skin, with a skin of a few kicks' travel
// (NeighbourShells with its own grid of centres, separate from the engine's pair search):
//  - at each kick, a particle that could leave its shell before h (|r_i - c_i| + |v_i| h
//    + |g| h^2 / 2 > skin / 2) gets a new shell centred where it is (refresh());
//  - a particle whose travel alone exceeds skin / 2 is "wide": the engine scans its full
//    neighbourhood instead;
//  - every other pair then stays more than R_i + R_j apart until h, so it cannot collide before
//    the next kick.
#include <cstdint>
#include <vector>

#include "libgran/core/box.hpp"
#include "libgran/core/vec.hpp"
#include "libgran/engines/event_driven/cell_list.hpp"
#include "libgran/engines/event_driven/neighbour_shells.hpp"

namespace gran {

template <int D>
class KickNeighbours {
  public:
    using Index = typename NeighbourShells<D>::Index;
    using Sizes = typename NeighbourShells<D>::Sizes;

    bool built() const { return built_; }
    bool refused() const { return refused_; }
    double skin() const { return skin_; }
    void clear() {
        built_ = false;
        lists_ = {};
        centres_ = {};
    }
    // Shells of width `skin` around every particle at r; false (nothing built) when lists
    // cannot serve (too many particles, or a periodic axis too short).
    bool build(const Box<D>& box, double skin, double width, const std::vector<Vec<D>>& r,
               Sizes sizes);
    template <class Travel>
    std::size_t refresh(const Box<D>& box, const std::vector<Vec<D>>& r, Sizes sizes, Travel travel,
                        std::vector<std::uint32_t>& wide) {
        const double half = 0.5 * skin_ * (1.0 - 1e-9);
        std::size_t moved = 0;
        for (std::uint32_t i = 0; i < r.size(); ++i) {
            const double reach = travel(i);
            if (reach > half) {
                wide.push_back(i);
                continue;
            }
            const double d = box.separation(r[i], lists_.centre(i)).norm();
            if (d + reach > half) {
                lists_.rebuild(i, r[i], box, centres_, sizes);
                ++moved;
            }
        }
        return moved;
    }
    const Index* list(std::uint32_t i) const { return lists_.list(i); }
    std::size_t size(std::uint32_t i) const { return lists_.size(i); }

  private:
    bool built_ = false;
    bool refused_ = false;
    double skin_ = 0;
    NeighbourShells<D> lists_;
    CellList<D> centres_;
};

extern template class KickNeighbours<2>;
extern template class KickNeighbours<3>;

}  // namespace gran
