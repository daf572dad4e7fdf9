#pragma once
// Test helper: the square (2D) or cubic (3D) box that holds the species table's particles at
// packing fraction phi.
#include <cmath>

#include "libgran/core/box.hpp"
#include "libgran/core/species.hpp"

namespace gran::testing {

template <int D>
Box<D> cube_for(const SpeciesTable& t, double phi, bool periodic) {
    Box<D> box;
    const double vd = D == 2 ? M_PI / 4 : M_PI / 6;
    double v = 0;
    for (const auto& s : t.species) v += double(s.count) * vd * std::pow(s.diameter, D);
    box.length = Vec<D>::Constant(std::pow(v / phi, 1.0 / D));
    box.periodic.fill(periodic);
    return box;
}

}  // namespace gran::testing
