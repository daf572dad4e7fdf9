#pragma once
// The pending events of the event-driven engine: one per particle, ordered by the event queue
// (event_queue.hpp: a 4-ary heap, or a calendar of time slices at large N). A particle's pending
// event is one 32-byte record (time, kind, code, the partner's counter, the kept collision): an
// event reads and writes all of them, and at N = 10^6, where the particle of each event is a random
// one, six parallel arrays were six cache lines from memory per event and the record is one.
//  - An event is a collision (code: the partner), a cell crossing, a wall hit or a periodic wrap
//    (code: 2 axis + side), a neighbour-shell exit, or none.
//  - Invalidation is lazy: a collision stores the partner's collision counter at prediction; if
//    the partner has changed velocity since, the event is stale and is simply re-predicted.
//  - The earliest collision of the last neighbour scan is kept apart from the event (kept_time,
//    kept_partner): after a cell crossing the engine scans only the newly adjacent cells and
//    compares with it.
// Times are the engine's internal (relative) times.
#include <cstdint>
#include <vector>

#include "libgran/core/cache_line.hpp"
#include "libgran/core/vec.hpp"
#include "libgran/engines/event_driven/event_queue.hpp"
#include "libgran/engines/event_driven/reorder.hpp"

namespace gran {

enum class EventKind : std::uint8_t { none, collision, cell, wall, shell, wrap };

class Scheduler {
  public:
    // n particles, none with an event; `calendar`: the queue's layout (event_queue.hpp).
    void reset(std::size_t n, bool calendar) {
        pending_.assign(n, Pending{});
        queue_.reset(n, calendar);
    }
    bool calendar() const { return queue_.calendar(); }

    // The earliest collision of a scan (partner -1: none) and, if any, the partner's collision
    // counter then.
    void keep_collision(std::uint32_t i, double time, std::int32_t partner,
                        std::uint32_t partner_count) {
        Pending& e = pending_[i];
        e.kept_time = time;
        e.kept_partner = partner;
        if (partner >= 0) e.partner_count = partner_count;
    }
    double kept_time(std::uint32_t i) const { return pending_[i].kept_time; }
    std::int32_t kept_partner(std::uint32_t i) const { return pending_[i].kept_partner; }
    std::uint32_t partner_count(std::uint32_t i) const { return pending_[i].partner_count; }

    // The pending event of i. In the event loop, commit(i) then moves i in the queue; after
    // setting every particle's event, rebuild() orders them all at once (O(N)).
    void set(std::uint32_t i, double time, EventKind kind, std::int32_t code) {
        Pending& e = pending_[i];
        e.time = time;
        e.kind = kind;
        e.code = code;
    }
    void commit(std::uint32_t i) { queue_.update(i, pending_[i].time); }
    void rebuild() {
        queue_.rebuild([this](std::uint32_t k) { return pending_[k].time; });
    }
    // rebuild() into a plain heap, whatever the layout was (EventDrivenEngine::
    // velocities_changed: a queue rebuilt at every thermostat kick).
    void rebuild_as_heap() {
        queue_.reset(pending_.size(), false);
        rebuild();
    }

    std::uint32_t next() const { return queue_.top(); }
    double next_time() const { return queue_.top_time(); }
    EventKind kind(std::uint32_t i) const { return pending_[i].kind; }
    std::int32_t code(std::uint32_t i) const { return pending_[i].code; }

    // The engine's time origin moved forward by dt.
    void shift(double dt) {
        for (Pending& e : pending_) {
            e.time -= dt;
            e.kept_time -= dt;
        }
        rebuild();
    }
    // The particles were re-sorted (order[k]: old index of the particle now at k, inv: its
    // inverse): the events follow them, and the queue is rebuilt from scratch.
    void reorder(const std::vector<std::uint32_t>& order, const std::vector<std::uint32_t>& inv) {
        apply_order(pending_, order);
        for (Pending& e : pending_) {
            if (e.kind == EventKind::collision) e.code = std::int32_t(inv[std::size_t(e.code)]);
            if (e.kept_partner >= 0)
                e.kept_partner = std::int32_t(inv[std::size_t(e.kept_partner)]);
        }
        queue_.reset(pending_.size(), queue_.calendar());
        rebuild();
    }

    void checkpoint(StateArchive& ar) {
        ar.section("event scheduler");
        ar.io(pending_);
        ar.io(queue_);
    }

  private:
    struct alignas(32) Pending {
        double time = kInf;
        double kept_time = kInf;          // earliest collision of the last scan
        std::int32_t code = -1;           // partner, or 2 axis + side
        std::int32_t kept_partner = -1;   // its partner (-1: none)
        std::uint32_t partner_count = 0;  // the partner's collision counter at prediction
        EventKind kind = EventKind::none;
        std::uint8_t unused[3] = {0, 0, 0};  // named, so a checkpoint's bytes are all defined
    };
    static_assert(sizeof(Pending) == 32);
    std::vector<Pending, CacheLineAllocator<Pending>> pending_;  // two records per cache line
    EventQueue queue_;
};

}  // namespace gran
