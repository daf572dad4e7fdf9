// The event-driven engine with neighbour shells (neighbour_shells.hpp): which pair search a scene
// gets, and the predictions and events that differ from the cell list's.
#include <numbers>
#include <stdexcept>

#include "libgran/engines/event_driven/engine.hpp"

namespace gran {

double choose_neighbour_skin(int dimension, double packing_fraction, std::size_t particles) {
    // Measured with gran_bench --skin, shells against cells side by side (docs/performance.md,
    // "Neighbour shells"). Shells win only in dense 3D gases small enough for their lists to stay
    // in cache: at N = 10976 with skin 0.5, 1.13-1.26x cells' rate at phi 0.45 and 1.29-1.36x at
    // 0.5, but 0.90-0.98x at 0.4 and 0.64x at 0.3 (particles leave their shells too often, and a
    // rebuild scans 27 cells of centres); at phi 0.45, 1.03-1.13x at N = 3e4 and 0.85-0.92x at 5e4.
    // In 2D (phi 0.6-0.75, skins 0.5 and 0.7) shells were 0.72-1.2x cells, no clear gain anywhere.
    if (dimension != 3 || particles > 40000) return 0.0;
    return packing_fraction >= 0.43 ? 0.5 : 0.0;
}

template <int D>
void EventDrivenEngine<D>::set_up_pair_search() {
    const double dmax = largest_diameter();
    double skin = settings_.neighbour_skin;
    if (skin > 0.0 && gravity_) {
        // Under gravity the shell exit is the root of a quartic; the cells' crossings are not.
        throw std::invalid_argument(
            "EventDrivenEngine: neighbour shells need a scene without gravity");
    }
    if (skin < 0.0) {
        double volume = 1.0, occupied = 0.0;
        for (int a = 0; a < D; ++a) volume *= box_.length[a];
        for (std::uint32_t s : p_.species) {
            const double r = radius_[s];
            occupied +=
                D == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
        }
        skin = gravity_ ? 0.0 : choose_neighbour_skin(D, occupied / volume, p_.size());
    }
    if (skin > 0.0) {
        // The grid holds the shells' centres: cells at least 2 R_max + skin wide.
        cells_.build(box_, dmax * (1.0 + skin), p_.r, settings_.cell_layout);
        if (cells_.image_offsets().empty()) {
            shells_on_ = true;
            shells_.build(box_, skin * dmax, p_.r, cells_, sizes());
            set_shell_bounds();
            return;
        }
        // A periodic axis shorter than 4 cells would need images of the lists' partners.
        if (settings_.neighbour_skin > 0.0) {
            throw std::invalid_argument(
                "EventDrivenEngine: neighbour shells need periodic axes at least 4 (1 + skin) "
                "largest diameters long");
        }
    }
    cells_.build(box_, dmax, p_.r, settings_.cell_layout);
}

template <int D>
void EventDrivenEngine<D>::set_shell_bounds() {
    // A list holds the particles whose centres lie within reach = (R_i + R_j + skin)(1 + 1e-9)
    // of i's centre, and each particle stays within skin / 2 of its own centre. With i's centre
    // at least m = 2 (R_max + skin) from both faces of a periodic axis, every member's position
    // is inside the box (at least skin / 2 - 1e-9 m from a face, not wrapped) and within
    // reach + skin <= m (1 + 1e-9) < L / 2 of i's, as m <= L / 4: the minimum image is then the
    // plain difference, and predict_in_shell skips it. Shorter axes never do.
    const double m = largest_diameter() + 2.0 * shells_.skin();
    for (int a = 0; a < D; ++a) {
        const double length = box_.length[a];
        if (!box_.periodic[a]) {
            shell_lo_[a] = -kInf;
            shell_hi_[a] = kInf;
        } else if (length >= 4.0 * m) {
            shell_lo_[a] = m;
            shell_hi_[a] = length - m;
        } else {
            shell_lo_[a] = kInf;
            shell_hi_[a] = -kInf;
        }
    }
}

template <int D>
void EventDrivenEngine<D>::schedule_in_shell(std::uint32_t i, Earliest& next) {
    const Vec<D>& x = p_.r[i];
    const Vec<D>& v = p_.v[i];
    next.consider(
        shell_exit_time<D>(box_.separation(x, shells_.centre(i)), v, 0.5 * shells_.skin()),
        EventKind::shell, 0);
    for (int a = 0; a < D; ++a) {
        if (box_.periodic[a]) {
            // Positions stay in the box: a wrap at each periodic boundary.
            if (v[a] == 0.0) continue;
            const int up = v[a] > 0.0 ? 1 : 0;
            next.consider(std::max(((up ? box_.length[a] : 0.0) - x[a]) / v[a], 0.0),
                          EventKind::wrap, 2 * a + up);
            continue;
        }
        EventKind k = EventKind::none;
        int c = 0;
        const double t = wall_event(i, a, next.time, kInf, k, c);
        next.consider(t, k, c);
    }
}

template <int D>
void EventDrivenEngine<D>::leave_shell(std::uint32_t i) {
    move(i);
    shells_.rebuild(i, p_.r[i], box_, cells_, sizes());
    ++counters_.shell_exits;
    repredict(i);
}

template <int D>
void EventDrivenEngine<D>::wrap(std::uint32_t i, int code) {
    move(i);
    const int a = code / 2;
    if (code % 2) {
        p_.r[i][a] -= box_.length[a];
        ++p_.image[i][std::size_t(a)];
    } else {
        p_.r[i][a] += box_.length[a];
        --p_.image[i][std::size_t(a)];
    }
    ++counters_.wraps;
    // The trajectories are unchanged: the kept collision stands unless its partner has changed
    // since (then it re-predicted, and i scans again).
    const std::int32_t old = events_.kept_partner(i);
    if (old >= 0 && count_[std::size_t(old)] != events_.partner_count(i)) {
        predict_in_shell(i);
    } else {
        schedule(i, old >= 0 ? events_.kept_time(i) - now_ : kInf, old);
    }
    events_.commit(i);
}

#define GRAN_INSTANTIATE(D)                                                          \
    template void EventDrivenEngine<D>::set_up_pair_search();                        \
    template void EventDrivenEngine<D>::set_shell_bounds();                          \
    template void EventDrivenEngine<D>::schedule_in_shell(std::uint32_t, Earliest&); \
    template void EventDrivenEngine<D>::leave_shell(std::uint32_t);                  \
    template void EventDrivenEngine<D>::wrap(std::uint32_t, int);
GRAN_INSTANTIATE(2)
GRAN_INSTANTIATE(3)
#undef GRAN_INSTANTIATE

}  // namespace gran
