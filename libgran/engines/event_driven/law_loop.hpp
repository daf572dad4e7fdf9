#pragma once
// The event loop of the event-driven engine templated on the hard-sphere law
// (libgran/plugins/law.hpp): the loop itself, binary collisions and wall hits, the parts that read
// the law. Included by libgran/engines/register_law.hpp, so each law's file instantiates them with
// its own law type (its restitution inlined, no call per collision); the engine reaches the loop
// through EventDrivenLawLoops, once per advance.
#include <algorithm>
#include <cmath>
#include <string>

#include "libgran/core/registry.hpp"
#include "libgran/engines/event_driven/engine.hpp"

namespace gran {

template <int D>
template <class L>
int EventDrivenEngine<D>::advance_with(double t_limit, std::uint64_t collision_limit,
                                       const std::atomic<bool>* interrupt,
                                       std::uint64_t event_limit) {
    // Internal times are relative to t_origin_ (see rebase_time()).
    double limit = t_limit - t_origin_;
    if (p_.size() == 0) {
        now_ = limit;
        limit_now_ = t_limit;
        return int(Stop::TimeLimit);
    }
    // The flag is read on entry (runs made of many short advances, e.g. frequent thermostat
    // kicks, must stop too) and every 1024 events.
    if (interrupt && interrupt->load(std::memory_order_relaxed)) return int(Stop::Interrupted);
    std::uint32_t check = 0;
    while (true) {
        if (interrupt && (++check & 1023u) == 0 && interrupt->load(std::memory_order_relaxed)) {
            return int(Stop::Interrupted);
        }
        if (counters_.events >= event_limit) return int(Stop::EventLimit);
        if (events_since_sort_ >= sort_every_) {
            // Between events the state is consistent: move the time origin, re-sort.
            rebase_time();
            limit = t_limit - t_origin_;
            sort_by_cell();
            events_since_sort_ = 0;
        }
        // Pop.
        const double te = events_.next_time();
        if (te > limit) {
            now_ = limit;
            limit_now_ = t_limit;  // now() reports the limit exactly
            return int(Stop::TimeLimit);
        }
        if (te >= 1e299) return int(Stop::NoEvents);
        const std::uint32_t i = events_.next();
        now_ = te;
        limit_now_ = kNoLimit;
        ++counters_.events;
        ++events_since_sort_;
        // Validate and dispatch.
        switch (events_.kind(i)) {
            case EventKind::collision: {
                const auto j = static_cast<std::uint32_t>(events_.code(i));
                if (count_[j] != events_.partner_count(i)) {
                    ++counters_.stale_events;
                    move(i);
                    repredict(i);
                    continue;
                }
                collide<L>(i, j);
                if (counters_.collisions >= collision_limit) return int(Stop::CollisionLimit);
                break;
            }
            case EventKind::cell:
                cross_cell(i, events_.code(i));
                break;
            case EventKind::wall:
                hit_wall<L>(i, events_.code(i));
                break;
            case EventKind::shell:
                leave_shell(i);
                break;
            case EventKind::wrap:
                wrap(i, events_.code(i));
                break;
            default:
                move(i);
                repredict(i);
                break;
        }
    }
}

template <int D>
template <class L>
void EventDrivenEngine<D>::collide(std::uint32_t i, std::uint32_t j) {
    if (shells_on_) {
        // Both partners scan their lists next: ask for the rows and centres now, so that the
        // misses on them (most of predict_in_shell's own time at 3D phi 0.5) overlap the
        // collision's arithmetic instead of following it.
        __builtin_prefetch(shells_.list(i) - 1);
        __builtin_prefetch(shells_.list(j) - 1);
        __builtin_prefetch(&shells_.centre(i));
        __builtin_prefetch(&shells_.centre(j));
    }
    move(i);
    move(j);
    const std::uint32_t si = p_.species[i], sj = p_.species[j];
    const double sigma_ij = radius_[si] + radius_[sj];
    const Vec<D> dr = box_.separation(p_.r[i], p_.r[j]);
    const double dist = dr.norm();
    const Vec<D> n = dr / dist;
    if (dist < sigma_ij * (1.0 - 1e-10)) ++counters_.overlap_collisions;
    const typename L::Pair& law = contacts_.template contacts<L>()[contacts_.pair_index(si, sj)];
    double alpha;
    if constexpr (L::impact_dependent) {
        // r(v) laws take the normal relative speed at impact (McNamara & Falcon 2005, Eq. 1).
        alpha = L::normal_restitution(law, (p_.v[i] - p_.v[j]).dot(n));
    } else {
        alpha = L::normal_restitution(law, 0.0);
    }
    double beta = L::tangential_restitution(law);
    if (settings_.tc_guard &&
        (now_ - last_collision_[i] < settings_.tc || now_ - last_collision_[j] < settings_.tc)) {
        alpha = 1.0;
        beta = -1.0;
        ++counters_.tc_collisions;
    }
    CollisionRecord<D> rec;
    if (sink_) record_before(rec, i, j, n, alpha, beta, sigma_ij);
    double impulse;
    if (rough_) {
        impulse = rough_collision<D>(p_.v[i], p_.v[j], p_.w[i], p_.w[j], mass_[si], mass_[sj],
                                     diameter_[si], diameter_[sj], inertia_[si], inertia_[sj], n,
                                     alpha, beta);
    } else {
        impulse = smooth_collision<D>(p_.v[i], p_.v[j], mass_[si], mass_[sj], n, alpha);
    }
    last_collision_[i] = now_;
    last_collision_[j] = now_;
    ++count_[i];
    ++count_[j];
    ++counters_.collisions;
    pair_collisions_.add(std::min(si, sj), std::max(si, sj));
    if (sink_) notify(rec, i, j, impulse);
    repredict(i);
    repredict(j);
}

// A wall hit: a rule replacing the contact (a thermal wall), or the contact law against the wall
// partner, v_n' - u = -e (v_n - u) (wall_collision) with e of the impact speed |v_n - u|.
template <int D>
template <class L>
void EventDrivenEngine<D>::hit_wall(std::uint32_t i, int code) {
    move(i);
    const int a = code / 2;
    const int side = code % 2;
    const double inward = side ? -1.0 : 1.0;
    const WallSlot& w = walls_[std::size_t(code)];
    const double t_abs = t_origin_ + now_;  // wall motions are functions of absolute time
    const double u = wall_velocity(w.motion, side ? -1 : 1, t_abs);
    const double before = p_.v[i][a];
    // Only a particle still moving into the wall (relative to it) is reflected.
    if (inward * (before - u) < 0.0) {
        // TC model at walls too: a hit within tc of the last collision is elastic.
        const bool guarded = settings_.tc_guard && now_ - last_collision_[i] < settings_.tc;
        if (guarded) ++counters_.tc_wall_hits;
        if (w.reflection) {
            w.reflection->reflect(p_.v[i], a, inward, u, mass_[p_.species[i]]);
        } else {
            const typename L::Pair& law =
                contacts_.template contacts<L>()[contacts_.wall_index(w.partner, p_.species[i])];
            const double e = guarded ? 1.0 : L::normal_restitution(law, before - u);
            p_.v[i][a] = wall_collision(before, u, e);
        }
    }
    finish_wall_hit(i, code, u, t_abs, before);
}

// Registers the event loops of law L for disks and spheres (called by register_law<L>).
template <class L>
void register_event_driven_loops(const std::string& name) {
    Registry<EventDrivenLawLoops<2>>::instance().add(
        {name, &EventDrivenEngine<2>::template advance_with<L>});
    Registry<EventDrivenLawLoops<3>>::instance().add(
        {name, &EventDrivenEngine<3>::template advance_with<L>});
}

}  // namespace gran
