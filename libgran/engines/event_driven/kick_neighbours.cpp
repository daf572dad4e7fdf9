#include "libgran/engines/event_driven/kick_neighbours.hpp"

namespace gran {

template <int D>
bool KickNeighbours<D>::build(const Box<D>& box, double skin, double width,
                              const std::vector<Vec<D>>& r, Sizes sizes) {
    clear();
    if (r.size() > NeighbourShells<D>::kMaxParticles) {
        refused_ = true;
        return false;
    }
    centres_.build(box, width, r);
    if (!centres_.image_offsets().empty()) {
        centres_ = {};
        refused_ = true;
        return false;
    }
    lists_.build(box, skin, r, centres_, sizes);
    skin_ = skin;
    built_ = true;
    return true;
}

template class KickNeighbours<2>;
template class KickNeighbours<3>;

}  // namespace gran
