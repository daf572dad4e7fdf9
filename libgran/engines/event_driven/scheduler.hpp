#pragma once
// The pending events of the event-driven engine: one per particle, ordered by an indexed 4-ary
// heap (event_queue.hpp), in flat per-particle arrays.
//  - An event is a collision (code: the partner), a cell crossing or a wall hit (code: 2 axis +
//    side), or none.
//  - Invalidation is lazy: a collision stores the partner's collision counter at prediction; if
//    the partner has changed velocity since, the event is stale and is simply re-predicted.
//  - The earliest collision of the last neighbour scan is kept apart from the event (kept_time,
//    kept_partner): after a cell crossing the engine scans only the newly adjacent cells and
//    compares with it.
// Times are the engine's internal (relative) times.
#include <cstdint>
#include <vector>

#include "libgran/core/vec.hpp"
#include "libgran/engines/event_driven/event_queue.hpp"
#include "libgran/engines/event_driven/reorder.hpp"

namespace gran {

enum class EventKind : std::uint8_t { none, collision, cell, wall };

class Scheduler {
  public:
    // n particles, none with an event.
    void reset(std::size_t n) {
        time_.assign(n, kInf);
        code_.assign(n, -1);
        partner_count_.assign(n, 0);
        kept_time_.assign(n, kInf);
        kept_partner_.assign(n, -1);
        kind_.assign(n, EventKind::none);
        queue_.reset(n);
    }

    // The earliest collision of a scan (partner -1: none) and, if any, the partner's collision
    // counter then.
    void keep_collision(std::uint32_t i, double time, std::int32_t partner,
                        std::uint32_t partner_count) {
        kept_time_[i] = time;
        kept_partner_[i] = partner;
        if (partner >= 0) partner_count_[i] = partner_count;
    }
    double kept_time(std::uint32_t i) const { return kept_time_[i]; }
    std::int32_t kept_partner(std::uint32_t i) const { return kept_partner_[i]; }
    std::uint32_t partner_count(std::uint32_t i) const { return partner_count_[i]; }

    // The pending event of i. In the event loop, commit(i) then moves i in the queue; after
    // setting every particle's event, rebuild() orders them all at once (O(N)).
    void set(std::uint32_t i, double time, EventKind kind, std::int32_t code) {
        time_[i] = time;
        kind_[i] = kind;
        code_[i] = code;
    }
    void commit(std::uint32_t i) { queue_.update(i, time_[i]); }
    void rebuild() {
        queue_.rebuild([this](std::uint32_t k) { return time_[k]; });
    }

    std::uint32_t next() const { return queue_.top(); }
    double next_time() const { return queue_.top_time(); }
    EventKind kind(std::uint32_t i) const { return kind_[i]; }
    std::int32_t code(std::uint32_t i) const { return code_[i]; }

    // The engine's time origin moved forward by dt.
    void shift(double dt) {
        for (std::size_t i = 0; i < time_.size(); ++i) {
            time_[i] -= dt;
            kept_time_[i] -= dt;
        }
        rebuild();
    }
    // The particles were re-sorted (order[k]: old index of the particle now at k, inv: its
    // inverse): the events follow them, and the queue is rebuilt from scratch.
    void reorder(const std::vector<std::uint32_t>& order, const std::vector<std::uint32_t>& inv) {
        apply_order(time_, order);
        apply_order(code_, order);
        apply_order(partner_count_, order);
        apply_order(kind_, order);
        apply_order(kept_time_, order);
        apply_order(kept_partner_, order);
        for (std::size_t k = 0; k < kind_.size(); ++k) {
            if (kind_[k] == EventKind::collision)
                code_[k] = std::int32_t(inv[std::size_t(code_[k])]);
            if (kept_partner_[k] >= 0)
                kept_partner_[k] = std::int32_t(inv[std::size_t(kept_partner_[k])]);
        }
        queue_.reset(time_.size());
        rebuild();
    }

    void checkpoint(StateArchive& ar) {
        ar.section("event scheduler");
        ar.io(time_);
        ar.io(code_);
        ar.io(partner_count_);
        ar.io(kept_time_);
        ar.io(kept_partner_);
        ar.io(kind_);
        ar.io(queue_);
    }

  private:
    std::vector<double> time_;
    std::vector<std::int32_t> code_;            // partner, or 2 axis + side
    std::vector<std::uint32_t> partner_count_;  // the partner's collision counter at prediction
    std::vector<double> kept_time_;             // earliest collision of the last scan
    std::vector<std::int32_t> kept_partner_;    // its partner (-1: none)
    std::vector<EventKind> kind_;
    EventQueue queue_;
};

}  // namespace gran
