// Close-packed initial configurations: a centred rectangular lattice in 2D (hexagonal when its
// cells are sqrt(3) times taller than wide) and a face-centred cubic lattice in 3D, stretched to
// fit the box. They reach packing fractions up to the densest packing (pi / sqrt(12) for disks,
// pi / sqrt(18) for spheres), above which random insertion (jamming near 0.55 in 2D and 0.38 in
// 3D, random sequential adsorption) and the square/cubic lattice (pi/4, pi/6) cannot go.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "libgran/plugins/placement.hpp"
#include "libgran/scene/placement.hpp"

namespace gran {

namespace {

// Basis of the conventional cell, in cell units: 2 sites (2D centred rectangular), 4 (fcc).
template <int D>
std::vector<std::array<double, D>> basis() {
    if constexpr (D == 2) {
        return {{0.0, 0.0}, {0.5, 0.5}};
    } else {
        return {{0.0, 0.0, 0.0}, {0.5, 0.5, 0.0}, {0.5, 0.0, 0.5}, {0.0, 0.5, 0.5}};
    }
}

// Site spacing along an axis with m cells: periodic, cells of L / m; bounded, the sites span
// [r, L - r] (cell coordinates 0 ... m - 1/2).
double cell_size(double length, bool periodic, std::int64_t m, double dmax) {
    return periodic ? length / double(m) : (length - dmax) / (double(m) - 0.5);
}

// Smallest centre distance of the lattice with cells c (nearest images included).
template <int D>
double nearest_distance(const std::array<double, D>& c) {
    double best = *std::min_element(c.begin(), c.end());  // same basis site, next cell
    const auto b = basis<D>();
    for (std::size_t k = 1; k < b.size(); ++k) {
        double s = 0;
        for (int a = 0; a < D; ++a) s += std::pow(b[k][std::size_t(a)] * c[std::size_t(a)], 2);
        best = std::min(best, std::sqrt(s));
    }
    return best;
}

}  // namespace

template <int D>
Particles<D> place_close_packed(const Box<D>& box, const SpeciesTable& table, Rng& rng) {
    const std::size_t n = table.total_count();
    const double dmax = table.max_diameter();
    const std::size_t nb = basis<D>().size();
    // Cells per axis: the choice with at least n sites whose nearest distance is largest.
    const auto m_max = static_cast<std::int64_t>(std::ceil(std::pow(double(n), 1.0 / D))) + 2;
    std::array<std::int64_t, D> best_m{};
    double best_dist = -1;
    std::array<std::int64_t, D> m;
    m.fill(1);
    while (true) {
        std::int64_t cells = 1;
        for (auto k : m) cells *= k;
        if (std::size_t(cells) * nb >= n) {
            std::array<double, D> c;
            bool ok = true;
            for (int a = 0; a < D; ++a) {
                c[std::size_t(a)] =
                    cell_size(box.length[a], box.periodic[std::size_t(a)], m[std::size_t(a)], dmax);
                ok = ok && c[std::size_t(a)] > 0;
            }
            const double dist = ok ? nearest_distance<D>(c) : -1;
            if (dist > best_dist) {
                best_dist = dist;
                best_m = m;
            }
        }
        int a = 0;
        while (a < D && ++m[std::size_t(a)] > m_max) m[std::size_t(a++)] = 1;
        if (a == D) break;
    }
    if (best_dist < dmax * (1 + 1e-12)) {
        throw PlacementError(fmt::format(
            "close_packed placement failed: the densest {} lattice that fits {} particles in this "
            "box has neighbours {:.6g} apart, less than the largest diameter {:.6g}; enlarge the "
            "box or lower the packing fraction (at most {:.4f} for {}, less on bounded axes)",
            D == 2 ? "hexagonal" : "fcc", n, best_dist, dmax, max_packing_fraction(D),
            D == 2 ? "disks" : "spheres"));
    }
    // Sites in cell order; n of them taken at an even stride, so vacancies spread over the box.
    std::vector<Vec<D>> sites;
    std::array<double, D> c;
    for (int a = 0; a < D; ++a)
        c[std::size_t(a)] =
            cell_size(box.length[a], box.periodic[std::size_t(a)], best_m[std::size_t(a)], dmax);
    std::int64_t cells = 1;
    for (auto k : best_m) cells *= k;
    for (std::int64_t cell = 0; cell < cells; ++cell) {
        for (const auto& b : basis<D>()) {
            Vec<D> r;
            std::int64_t rest = cell;
            for (int a = 0; a < D; ++a) {
                const std::int64_t k = rest % best_m[std::size_t(a)];
                rest /= best_m[std::size_t(a)];
                const double u = double(k) + b[std::size_t(a)];
                r[a] = box.periodic[std::size_t(a)] ? (u + 0.25) * c[std::size_t(a)]
                                                    : 0.5 * dmax + u * c[std::size_t(a)];
            }
            sites.push_back(r);
        }
    }
    Particles<D> p;
    p.resize(n, false);
    std::vector<std::uint32_t> seq;
    for (std::uint32_t s = 0; s < table.size(); ++s)
        seq.insert(seq.end(), table.species[s].count, s);
    for (std::size_t k = seq.size(); k > 1; --k) {
        std::swap(seq[k - 1], seq[static_cast<std::size_t>(uniform01(rng) * double(k)) % k]);
    }
    for (std::size_t i = 0; i < n; ++i) {
        p.r[i] = sites[i * sites.size() / n];
        p.species[i] = seq[i];
    }
    return p;
}

template Particles<2> place_close_packed<2>(const Box<2>&, const SpeciesTable&, Rng&);
template Particles<3> place_close_packed<3>(const Box<3>&, const SpeciesTable&, Rng&);

namespace {

const bool registered = PlacementRegistry::instance().add(
    {{"close_packed",
      "hexagonal (2D) or fcc (3D) lattice stretched to the box, up to the densest packing; "
      "vacancies spread evenly, species shuffled",
      {}},
     [](const Box<2>& b, const SpeciesTable& t, Rng& r) { return place_close_packed<2>(b, t, r); },
     [](const Box<3>& b, const SpeciesTable& t, Rng& r) {
         return place_close_packed<3>(b, t, r);
     }});

}  // namespace

}  // namespace gran
