// The re-prediction of every particle at once, at the start and after a change of all
// velocities (a thermostat's kick): each pair timed once, and with a horizon (the next kick)
// only the pairs that can touch before it.
#include "libgran/engines/event_driven/engine.hpp"

namespace gran {

template <int D>
void EventDrivenEngine<D>::predict_all(double horizon) {
    // Every pair of neighbours is met twice in a per-particle pass (from i and from j), and after a
    // thermostat kick such passes are most of a heated run's work. Here each pair is met once: i
    // meets the particles stored after it in its own cell and every particle of the forward half
    // of its neighbour cells (CellList::forward_neighbours), and each collision time updates both
    // partners. The times are bit for bit those of the per-particle scan: separation(rj, ri) is
    // exactly -separation(ri, rj), so b, c and the root are the same numbers. One-cell periodic
    // axes (the image scan) keep the per-particle pass.
    const auto n = std::uint32_t(p_.size());
    if (!cells_.image_offsets().empty()) {
        for (std::uint32_t i = 0; i < n; ++i) predict(i);
        return;
    }
    // Scratch of 12 bytes per particle, freed on return (memory at N = 10^6).
    std::vector<double> all_best(n, kInf);
    std::vector<std::int32_t> all_partner(n, -1);
    double* best = all_best.data();
    std::int32_t* partner = all_partner.data();
    const Vec<D>* r = p_.r.data();
    const Vec<D>* v = p_.v.data();
    const std::uint32_t* species = p_.species.data();
    const double* radius = radius_.data();
    auto meet = [&](std::uint32_t i, std::uint32_t j) {
        const Vec<D> dr = box_.separation(r[i], r[j]);
        // Branch-free (as the scans): a pair the bound would have rejected gets a time later than
        // both bests, so nothing changes.
        const double t = pair_collision_time_branchless<D>(dr, v[i] - v[j],
                                                           radius[species[i]] + radius[species[j]]);
        if (t < best[i]) {
            best[i] = t;
            partner[i] = std::int32_t(j);
        }
        if (t < best[j]) {
            best[j] = t;
            partner[j] = std::int32_t(i);
        }
    };
    // With a horizon (the next thermostat kick, when every event is predicted again) most pairs
    // cannot touch before it, and multiplications alone tell them: the squared gap
    // f(s) = c + 2 b s + dv^2 s^2 stays positive on [0, h] when the pair recedes (b >= 0), or when
    // its minimum over [0, h] is positive (f(h) if the closest approach comes later, else
    // c - b^2 / dv^2, the sign of -disc). The test is branch-free (approaching or not is a coin
    // flip) and compacts the pairs left, which meet() times as without a horizon. h is widened by
    // 1e-6 of itself so that round-off never drops a collision before the horizon.
    const bool limited = horizon < kInf;
    const double h = std::max(horizon, 0.0) * (1 + 1e-6) + 1e-300;
    std::vector<std::uint32_t> near;
    auto meet_before_horizon = [&](std::uint32_t i, const auto* buf, std::size_t m, bool only_later)
        __attribute__((always_inline)) {
        if (m < 4) {  // too few for the two passes to pay (dilute gases): time them all
            for (std::size_t k = 0; k < m; ++k)
                if (!only_later || buf[k] > i) meet(i, buf[k]);
            return;
        }
        if (near.size() < m) near.resize(2 * m);
        std::uint32_t* out = near.data();
        std::size_t kept = 0;
        const Vec<D> ri = r[i], vi = v[i];
        const double radius_i = radius[species[i]];
        for (std::size_t k = 0; k < m; ++k) {
            const std::uint32_t j = buf[k];
            const Vec<D> dr = box_.separation(ri, r[j]);
            const Vec<D> dv = vi - v[j];
            const double sigma = radius_i + radius[species[j]];
            const double b = dr.dot(dv);
            const double dv2 = dv.squaredNorm();
            const double c = dr.squaredNorm() - sigma * sigma;
            const bool late = b + dv2 * h < 0.0;
            const bool touch =
                (late & (c + h * (2.0 * b + dv2 * h) <= 0.0)) | (!late & (b * b - dv2 * c > 0.0));
            out[kept] = j;
            kept += std::size_t((b < 0.0) & touch & (!only_later | (j > i)));
        }
        for (std::size_t q = 0; q < kept; ++q) meet(i, out[q]);
    };
    if (shells_on_) {
        // Every pair in the lists once, from its lower index.
        for (std::uint32_t i = 0; i < n; ++i) {
            const auto* list = shells_.list(i);
            if (limited) {
                meet_before_horizon(i, list, shells_.size(i), true);
                continue;
            }
            for (std::size_t k = 0, m = shells_.size(i); k < m; ++k) {
                if (list[k] > i) meet(i, list[k]);
            }
        }
        for (std::uint32_t i = 0; i < n; ++i) schedule(i, best[i], partner[i]);
        return;
    }
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::int32_t own = cells_.cell_of(i);
        std::size_t m = cells_.gather(&own, 1);
        const std::uint32_t* buf = cells_.candidates();
        std::int32_t cells[CellList<D>::kMaxNeighbours];
        if (limited) {
            meet_before_horizon(i, buf, m, true);
            m = cells_.gather(cells, cells_.forward_neighbours(i, cells));
            meet_before_horizon(i, buf, m, false);
            continue;
        }
        for (std::size_t k = 0; k < m; ++k) {
            if (buf[k] > i) meet(i, buf[k]);
        }
        m = cells_.gather(cells, cells_.forward_neighbours(i, cells));
        for (std::size_t k = 0; k < m; ++k) meet(i, buf[k]);
    }
    for (std::uint32_t i = 0; i < n; ++i) schedule(i, best[i], partner[i]);
}

template void EventDrivenEngine<2>::predict_all(double);
template void EventDrivenEngine<3>::predict_all(double);

}  // namespace gran
