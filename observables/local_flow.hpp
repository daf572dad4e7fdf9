#pragma once
// Velocities about the coarse-grained local flow (the `flow_cell` option of `temperatures`,
// `velocity_pdf` and `profiles`). The box is cut into cells about `flow_cell` long along each
// axis; a cell's flow velocity is its mass-weighted mean velocity U_c = sum_j m_j v_j / M_c, and
// a particle's peculiar velocity is c_i = v_i - U_c(i). In large heated or cooling boxes the
// velocity field has collective flow on long wavelengths; about the global centre-of-mass
// velocity it counts as heat (m_s <u^2> more in every species' temperature).
//
// Subtracting a cell's own mean also removes part of each particle's thermal motion: with one
// particle in a cell nothing is left. With c_i = sum_j w_ij v_j, w_ij = delta_ij - m_j / M_c, and
// the velocities of a cell independent about U_c with per-component variance v_t = T_t / m_t and
// Sonine coefficient a2_t (isotropic: per-component fourth cumulant 3 a2_t v_t^2), exactly
//   E[c_{i,a}^2] = sum_t G_{i,t} v_t,                       G_{i,t} = sum_{j in t} w_ij^2,
//   E[|c_i|^4]   = D (D + 2) [V_i^2 + sum_t W_{i,t} a2_t v_t^2],
//                  V_i = sum_t G_{i,t} v_t,                 W_{i,t} = sum_{j in t} w_ij^4.
// Summed over the particles of each species, these are linear equations for v_t, then a2_t, which
// the observables solve: unbiased estimates for any cell size (a cell needs two particles to count
// at all). One cell spanning the box gives back the centre-of-mass estimates up to O(1/N).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "libgran/core/particles.hpp"
#include "libgran/core/species.hpp"
#include "libgran/core/vec.hpp"

namespace gran {

template <int D>
class LocalFlow {
  public:
    LocalFlow() = default;
    // Cells of about `cell` (at least one per axis, whole numbers per box length).
    LocalFlow(double cell, std::span<const double> box_length, std::size_t species)
        : species_(species) {
        cells_ = 1;
        for (int a = 0; a < D; ++a) {
            const double l = box_length[std::size_t(a)];
            per_axis_[std::size_t(a)] = std::max<std::size_t>(1, std::size_t(std::floor(l / cell)));
            width_[std::size_t(a)] = l / double(per_axis_[std::size_t(a)]);
            cells_ *= per_axis_[std::size_t(a)];
        }
    }

    std::size_t cells() const { return cells_; }

    // Assigns every particle to its cell; the cells' masses per species, sums of m^2 and m^4,
    // and flow velocities.
    void compute(const Particles<D>& p, const SpeciesTable& table) {
        const std::size_t n = p.size();
        cell_of_.resize(n);
        mass_.assign(cells_ * species_, 0.0);
        m2_.assign(cells_ * species_, 0.0);
        m4_.assign(cells_ * species_, 0.0);
        total_.assign(cells_, 0.0);
        flow_.assign(cells_, Vec<D>::Zero());
        for (std::size_t i = 0; i < n; ++i) {
            std::size_t c = 0;
            for (int a = D - 1; a >= 0; --a) {
                const std::size_t k = per_axis_[std::size_t(a)];
                double x = p.r[i][a] / width_[std::size_t(a)];
                x -= double(k) * std::floor(x / double(k));  // periodic images into [0, k)
                c = c * k + std::min(k - 1, std::size_t(x));
            }
            cell_of_[i] = std::uint32_t(c);
            const std::uint32_t s = p.species[i];
            const double m = table.species[s].mass;
            mass_[c * species_ + s] += m;
            m2_[c * species_ + s] += m * m;
            m4_[c * species_ + s] += m * m * m * m;
            total_[c] += m;
            flow_[c] += m * p.v[i];
        }
        for (std::size_t c = 0; c < cells_; ++c) {
            if (total_[c] > 0) flow_[c] /= total_[c];
        }
    }

    const Vec<D>& flow_of(std::size_t i) const { return flow_[cell_of_[i]]; }
    std::size_t cell_of(std::size_t i) const { return cell_of_[i]; }

    // Adds G_{i,t} (t = 0 .. species - 1) of particle i (species s, mass m) to g[t].
    void add_variance_weights(std::size_t i, std::uint32_t s, double m, double* g) const {
        const std::size_t c = cell_of_[i];
        const double inv = 1.0 / total_[c], own = 1 - m * inv;
        for (std::size_t t = 0; t < species_; ++t) g[t] += m2_[c * species_ + t] * inv * inv;
        g[s] += own * own - m * m * inv * inv;
    }

    // Adds W_{i,t} of particle i to w[t].
    void add_quartic_weights(std::size_t i, std::uint32_t s, double m, double* w) const {
        const std::size_t c = cell_of_[i];
        const double inv = 1.0 / total_[c], own = 1 - m * inv;
        const double inv4 = inv * inv * inv * inv;
        for (std::size_t t = 0; t < species_; ++t) w[t] += m4_[c * species_ + t] * inv4;
        w[s] += own * own * own * own - m * m * m * m * inv4;
    }

    // Kinetic energy of the flow about the centre-of-mass velocity u, sum_c M_c |U_c - u|^2 / 2,
    // and its expectation if the velocities were independent at per-species temperatures T (no
    // collective flow): (D/2) [sum_c sum_t M_{t,c} T_t / M_c - sum_t M_t T_t / M], the last term
    // the noise u itself removes (one cell spanning the box has no flow).
    double flow_energy(const Vec<D>& u) const {
        double e = 0;
        for (std::size_t c = 0; c < cells_; ++c)
            e += 0.5 * total_[c] * (flow_[c] - u).squaredNorm();
        return e;
    }
    double uncorrelated_flow_energy(std::span<const double> T) const {
        double e = 0, whole = 0, mass = 0;
        for (std::size_t c = 0; c < cells_; ++c) {
            if (!(total_[c] > 0)) continue;
            for (std::size_t t = 0; t < species_; ++t) {
                e += 0.5 * D * mass_[c * species_ + t] * T[t] / total_[c];
                whole += 0.5 * D * mass_[c * species_ + t] * T[t];
            }
            mass += total_[c];
        }
        return e - whole / mass;
    }

  private:
    std::size_t species_ = 1, cells_ = 1;
    std::array<std::size_t, D> per_axis_{};
    std::array<double, D> width_{};
    std::vector<std::uint32_t> cell_of_;
    std::vector<double> mass_, m2_, m4_, total_;  // per cell (x species)
    std::vector<Vec<D>> flow_;
};

// Solves the dense n x n system a x = b (row-major a), Gaussian elimination with partial
// pivoting; n is the number of species (small). Returns NaN entries if a is singular.
inline std::vector<double> solve_small(std::vector<double> a, std::vector<double> b) {
    const std::size_t n = b.size();
    for (std::size_t k = 0; k < n; ++k) {
        std::size_t piv = k;
        for (std::size_t r = k + 1; r < n; ++r) {
            if (std::abs(a[r * n + k]) > std::abs(a[piv * n + k])) piv = r;
        }
        if (!(std::abs(a[piv * n + k]) > 0)) return std::vector<double>(n, std::nan(""));
        if (piv != k) {
            for (std::size_t c = 0; c < n; ++c) std::swap(a[k * n + c], a[piv * n + c]);
            std::swap(b[k], b[piv]);
        }
        for (std::size_t r = k + 1; r < n; ++r) {
            const double f = a[r * n + k] / a[k * n + k];
            for (std::size_t c = k; c < n; ++c) a[r * n + c] -= f * a[k * n + c];
            b[r] -= f * b[k];
        }
    }
    std::vector<double> x(n);
    for (std::size_t k = n; k-- > 0;) {
        double s = b[k];
        for (std::size_t c = k + 1; c < n; ++c) s -= a[k * n + c] * x[c];
        x[k] = s / a[k * n + k];
    }
    return x;
}

// The `flow_cell` parameter of an observable: refused when the cells would hold fewer than two
// particles on average (their peculiar velocities would be mostly the cells' own noise).
inline void check_flow_cell(double cell, std::span<const double> box_length, std::size_t particles,
                            int dimension, const std::function<void(const std::string&)>& fail) {
    double cells = 1;
    for (int a = 0; a < dimension; ++a)
        cells *= std::max(1.0, std::floor(box_length[std::size_t(a)] / cell));
    if (double(particles) / cells < 2) {
        fail(
            fmt::format("cells of {} hold {:.3g} particles on average; at least 2 are needed "
                        "(take a larger flow_cell)",
                        cell, double(particles) / cells));
    }
}

}  // namespace gran
