#include "libgran/scene/placement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <unordered_map>

#include "libgran/plugins/placement.hpp"

namespace gran {

double max_packing_fraction(int d) {
    return d == 2 ? std::numbers::pi / std::sqrt(12.0) : std::numbers::pi / std::sqrt(18.0);
}

template <int D>
double packing_fraction(const Box<D>& box, const SpeciesTable& table) {
    const double vd = D == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6;
    double v = 0;
    for (const auto& s : table.species) v += double(s.count) * vd * std::pow(s.diameter, D);
    return v / box.volume();
}

namespace {

template <int D>
std::vector<std::uint32_t> species_sequence(const SpeciesTable& table) {
    std::vector<std::uint32_t> seq;
    for (std::uint32_t s = 0; s < table.size(); ++s)
        seq.insert(seq.end(), table.species[s].count, s);
    return seq;
}

template <int D>
Particles<D> empty_particles(const SpeciesTable& table) {
    Particles<D> p;
    p.resize(table.total_count(), false);
    return p;
}

// Hash grid of the particles placed so far, cells at least dmax wide (random placement).
template <int D>
class PlacedGrid {
  public:
    PlacedGrid(const Box<D>& box, double dmax) : box_(box) {
        for (int a = 0; a < D; ++a) {
            nc_[a] = std::max<std::int64_t>(1, std::int64_t(box.length[a] / dmax));
            w_[a] = box.length[a] / double(nc_[a]);
        }
    }

    // Whether a particle of radius rad at r overlaps none of the placed particles of p: scans
    // the 3^D neighbourhood of its cell (wrapping periodic axes).
    bool free(const Vec<D>& r, double rad, const Particles<D>& p, const SpeciesTable& table) const {
        const std::array<std::int64_t, D> c = cell(r);
        for (int code = 0; code < (D == 2 ? 9 : 27); ++code) {
            std::array<std::int64_t, D> cn;
            int rest = code;
            bool inside = true;
            for (int a = 0; a < D; ++a) {
                cn[a] = c[a] + (rest % 3) - 1;
                rest /= 3;
                if (cn[a] < 0 || cn[a] >= nc_[a]) {
                    if (box_.periodic[a]) {
                        cn[a] = (cn[a] + nc_[a]) % nc_[a];
                    } else {
                        inside = false;
                    }
                }
            }
            if (!inside) continue;
            auto it = grid_.find(key(cn));
            if (it == grid_.end()) continue;
            for (std::uint32_t j : it->second) {
                const double sig = rad + 0.5 * table.species[p.species[j]].diameter;
                if (box_.separation(r, p.r[j]).squaredNorm() < sig * sig) return false;
            }
        }
        return true;
    }

    void add(const Vec<D>& r, std::uint32_t idx) { grid_[key(cell(r))].push_back(idx); }

  private:
    std::array<std::int64_t, D> cell(const Vec<D>& r) const {
        std::array<std::int64_t, D> c;
        for (int a = 0; a < D; ++a)
            c[a] = std::min<std::int64_t>(nc_[a] - 1, std::int64_t(r[a] / w_[a]));
        return c;
    }
    std::int64_t key(const std::array<std::int64_t, D>& c) const {
        std::int64_t k = 0;
        for (int a = D - 1; a >= 0; --a) k = k * nc_[a] + c[a];
        return k;
    }

    const Box<D>& box_;
    std::array<std::int64_t, D> nc_;
    Vec<D> w_;
    std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid_;
};

// A uniformly random position for a particle of radius rad, inside the walls of bounded axes.
template <int D>
Vec<D> random_position(const Box<D>& box, double rad, Rng& rng) {
    Vec<D> r;
    for (int a = 0; a < D; ++a) {
        const double lo = box.periodic[a] ? 0.0 : rad;
        const double hi = box.periodic[a] ? box.length[a] : box.length[a] - rad;
        r[a] = lo + (hi - lo) * uniform01(rng);
    }
    return r;
}

}  // namespace

template <int D>
Particles<D> place_random(const Box<D>& box, const SpeciesTable& table, Rng& rng,
                          std::size_t attempts) {
    Particles<D> p = empty_particles<D>(table);
    auto order = species_sequence<D>(table);
    // Largest first: small particles fill the gaps left by big ones.
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return table.species[a].diameter > table.species[b].diameter;
    });
    PlacedGrid<D> grid(box, table.max_diameter());
    const double phi = packing_fraction<D>(box, table);
    for (std::size_t idx = 0; idx < order.size(); ++idx) {
        const std::uint32_t s = order[idx];
        const double rad = 0.5 * table.species[s].diameter;
        bool placed = false;
        for (std::size_t attempt = 0; attempt < attempts && !placed; ++attempt) {
            const Vec<D> r = random_position<D>(box, rad, rng);
            if (grid.free(r, rad, p, table)) {
                p.r[idx] = r;
                p.species[idx] = s;
                grid.add(r, static_cast<std::uint32_t>(idx));
                placed = true;
            }
        }
        if (!placed) {
            throw PlacementError(fmt::format(
                "random placement failed: particle {} of {} (species '{}') found no free spot "
                "after {} "
                "attempts at packing fraction {:.4g}; use initial.placement: lattice (up to "
                "{:.4f}), "
                "close_packed (up to {:.4f}) or a lower packing fraction",
                idx + 1, order.size(), table.species[s].name, attempts, phi,
                D == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6, max_packing_fraction(D)));
        }
    }
    return p;
}

template <int D>
Particles<D> place_lattice(const Box<D>& box, const SpeciesTable& table, Rng& rng) {
    Particles<D> p = empty_particles<D>(table);
    const std::size_t n = p.size();
    const double dmax = table.max_diameter();
    // Choose sites per axis proportional to the box lengths, enough for n particles.
    std::array<std::int64_t, D> m;
    const double per = std::pow(box.volume() / double(std::max<std::size_t>(n, 1)), 1.0 / D);
    std::int64_t sites = 1;
    for (int a = 0; a < D; ++a) {
        m[a] = std::max<std::int64_t>(1, std::int64_t(std::floor(box.length[a] / per)));
        sites *= m[a];
    }
    for (int a = 0; sites < std::int64_t(n); a = (a + 1) % D) {
        sites = sites / m[a] * (m[a] + 1);
        ++m[a];
    }
    for (int a = 0; a < D; ++a) {
        if (box.length[a] / double(m[a]) < dmax * (1 + 1e-12)) {
            throw PlacementError(
                fmt::format("lattice placement failed: {} sites along axis {} are {:.4g} apart, "
                            "less than the largest "
                            "diameter {:.4g}; enlarge the box, lower the packing fraction or use "
                            "initial.placement: close_packed (hexagonal/fcc, up to {:.4f})",
                            m[a], a, box.length[a] / double(m[a]), dmax, max_packing_fraction(D)));
        }
    }
    std::vector<std::uint32_t> seq = species_sequence<D>(table);
    for (std::size_t k = seq.size(); k > 1; --k) {
        std::swap(seq[k - 1], seq[static_cast<std::size_t>(uniform01(rng) * double(k)) % k]);
    }
    for (std::size_t idx = 0; idx < n; ++idx) {
        std::size_t rest = idx;
        for (int a = 0; a < D; ++a) {
            const std::size_t k = rest % std::size_t(m[a]);
            rest /= std::size_t(m[a]);
            p.r[idx][a] = (double(k) + 0.5) * box.length[a] / double(m[a]);
        }
        p.species[idx] = seq[idx];
    }
    return p;
}

template <int D>
void maxwellian_velocities(Particles<D>& p, const SpeciesTable& table, double T, Rng& rng) {
    const std::size_t n = p.size();
    if (n == 0) return;
    Vec<D> momentum = Vec<D>::Zero();
    double mass_total = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const auto& s = table.species[p.species[i]];
        const double sd = std::sqrt(T / s.mass);
        for (int a = 0; a < D; ++a) p.v[i][a] = sd * gaussian(rng);
        momentum += s.mass * p.v[i];
        mass_total += s.mass;
    }
    const Vec<D> u = momentum / mass_total;
    double ke2 = 0;
    for (std::size_t i = 0; i < n; ++i) {
        p.v[i] -= u;
        ke2 += table.species[p.species[i]].mass * p.v[i].squaredNorm();
    }
    // With n = 1 the centre-of-mass motion is all there is: keep it at rest.
    if (n > 1 && ke2 > 0) {
        const double dof = double(D) * double(n - 1);
        const double scale = std::sqrt(T * dof / ke2);
        for (auto& v : p.v) v *= scale;
    }
    if (p.rotating()) {
        for (std::size_t i = 0; i < n; ++i) {
            const auto& s = table.species[p.species[i]];
            const double inertia = s.inertia_factor * s.mass * s.diameter * s.diameter / 4;
            const double sd = std::sqrt(T / inertia);
            if constexpr (D == 2) {
                p.w[i] = sd * gaussian(rng);
            } else {
                for (int a = 0; a < 3; ++a) p.w[i][a] = sd * gaussian(rng);
            }
        }
    }
}

template double packing_fraction<2>(const Box<2>&, const SpeciesTable&);
Particles<3> vibrated_bed_lattice(std::size_t n, double width, double z0, std::uint64_t seed) {
    Particles<3> p;
    p.resize(n, false);
    const auto per_row = static_cast<std::size_t>(std::floor(width / 1.2));
    const double spacing = width / double(per_row);
    Rng rng = make_rng(seed, Stream::Placement);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t layer = i / (per_row * per_row), k = i % (per_row * per_row);
        p.r[i] = Vec<3>((double(k % per_row) + 0.5) * spacing,
                        (double(k / per_row) + 0.5) * spacing, z0 + 1.2 * double(layer));
        for (int a = 0; a < 3; ++a) p.v[i][a] = 0.1 * (uniform01(rng) - 0.5);
    }
    // No centre-of-mass motion: a frictionless floor could not stop a horizontal drift.
    Vec<3> mean = Vec<3>::Zero();
    for (const auto& v : p.v) mean += v / double(n);
    for (auto& v : p.v) v -= mean;
    return p;
}

template double packing_fraction<3>(const Box<3>&, const SpeciesTable&);
template Particles<2> place_random<2>(const Box<2>&, const SpeciesTable&, Rng&, std::size_t);
template Particles<3> place_random<3>(const Box<3>&, const SpeciesTable&, Rng&, std::size_t);
template Particles<2> place_lattice<2>(const Box<2>&, const SpeciesTable&, Rng&);
template Particles<3> place_lattice<3>(const Box<3>&, const SpeciesTable&, Rng&);
template void maxwellian_velocities<2>(Particles<2>&, const SpeciesTable&, double, Rng&);

namespace {

const bool random_registered = PlacementRegistry::instance().add(
    {{"random",
      "random sequential insertion without overlaps, largest particles first (up to packing "
      "fractions of about 0.45 for disks, 0.3 for spheres)",
      {}},
     [](const Box<2>& b, const SpeciesTable& t, Rng& r) { return place_random<2>(b, t, r); },
     [](const Box<3>& b, const SpeciesTable& t, Rng& r) { return place_random<3>(b, t, r); }});

const bool lattice_registered = PlacementRegistry::instance().add(
    {{"lattice", "square (2D) or simple cubic (3D) lattice, species shuffled over the sites", {}},
     [](const Box<2>& b, const SpeciesTable& t, Rng& r) { return place_lattice<2>(b, t, r); },
     [](const Box<3>& b, const SpeciesTable& t, Rng& r) { return place_lattice<3>(b, t, r); }});

}  // namespace
template void maxwellian_velocities<3>(Particles<3>&, const SpeciesTable&, double, Rng&);

}  // namespace gran
