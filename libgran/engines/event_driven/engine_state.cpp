// The event-driven engine between events: the whole state brought to the present, changed by a
// driver, moved to a new time origin, or re-sorted by cell (engine.cpp holds the event loop).
#include "libgran/engines/event_driven/engine.hpp"

namespace gran {

template <int D>
void EventDrivenEngine<D>::rebase_time() {
    // Times are kept relative to an origin moved to the present now and then, so that relative
    // times stay small and keep their precision in long runs (absolute times near 1e6 would leave
    // position errors near 1e-10 diameters, and overlap-repair collisions).
    synchronize();
    const double shift = now_;
    if (shift == 0.0) return;
    for (std::size_t i = 0; i < p_.size(); ++i) {
        p_.t[i] = 0.0;
        last_collision_[i] -= shift;
    }
    events_.shift(shift);
    t_origin_ += shift;
    now_ = 0.0;
}

template <int D>
void EventDrivenEngine<D>::synchronize() {
    for (std::uint32_t i = 0; i < p_.size(); ++i) move(i);
}

template <int D>
void EventDrivenEngine<D>::velocities_changed(double next_change) {
    synchronize();
    for (std::uint32_t i = 0; i < p_.size(); ++i) ++count_[i];
    predict_all(next_change - t_origin_ - now_);
    // A scene whose velocities all change every few events (a thermostat's kicks) rebuilds its
    // queue at each change, and there the heap's rebuild is cheaper than the calendar's
    // redistribution: at N = 10^4 a heated gas ran 0.89-0.94x as fast on the calendar
    // (docs/performance.md, "The calendar from 4096 particles on"). The engine's own choice
    // turns to the heap at the first such change; a layout forced by the settings stays.
    if (settings_.queue_layout == QueueLayout::automatic && events_.calendar()) {
        events_.rebuild_as_heap();
    } else {
        events_.rebuild();
    }
    ++counters_.full_reschedules;
}

template <int D>
void EventDrivenEngine<D>::sort_by_cell() {
    // Particles stored in cell order: neighbours in space become neighbours in memory, so a cell
    // scan touches few cache lines (the storage stays structure-of-arrays).
    std::vector<std::uint32_t> order, inv;
    cells_.sort_order(order, inv);
    apply_order(p_.r, order);
    apply_order(p_.v, order);
    apply_order(p_.t, order);
    apply_order(p_.species, order);
    apply_order(p_.w, order);
    apply_order(p_.image, order);
    apply_order(id_, order);
    apply_order(count_, order);
    apply_order(last_collision_, order);
    events_.reorder(order, inv);
    cells_.reorder(order);
    if (shells_on_) shells_.reorder(order, inv);
    ++counters_.sorts;
}

template <int D>
void EventDrivenEngine<D>::checkpoint(StateArchive& ar) {
    ar.section("event_driven engine");
    ar.io(p_);
    ar.io(counters_);
    ar.io(now_);
    ar.io(t_origin_);
    ar.io(limit_now_);
    ar.io(count_);
    ar.io(last_collision_);
    ar.io(events_);
    ar.io(cells_);
    ar.io(shells_on_);
    if (shells_on_) {
        ar.io(shells_);
        set_shell_bounds();
    }
    ar.io(pair_collisions_);
    ar.io(wall_hit_count_);
    ar.io(wall_impulse_);
    ar.io(id_);
    ar.io(events_since_sort_);
    ar.io(sort_every_);
}

template void EventDrivenEngine<2>::rebase_time();
template void EventDrivenEngine<2>::synchronize();
template void EventDrivenEngine<2>::velocities_changed(double);
template void EventDrivenEngine<2>::sort_by_cell();
template void EventDrivenEngine<3>::rebase_time();
template void EventDrivenEngine<3>::synchronize();
template void EventDrivenEngine<3>::velocities_changed(double);
template void EventDrivenEngine<3>::sort_by_cell();
template void EventDrivenEngine<2>::checkpoint(StateArchive&);
template void EventDrivenEngine<3>::checkpoint(StateArchive&);

}  // namespace gran
