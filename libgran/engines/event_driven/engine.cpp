#include "libgran/engines/event_driven/engine.hpp"

#include <emmintrin.h>

#include <stdexcept>

#include "libgran/core/registry.hpp"

namespace gran {

template <int D>
EventDrivenEngine<D>::EventDrivenEngine(const Box<D>& box, const SpeciesTable& table,
                                        const ContactTable& contacts, Particles<D> particles,
                                        EngineSettings settings)
    : box_(box), p_(std::move(particles)), settings_(settings), contacts_(contacts) {
    p_.image.resize(p_.size());  // particles built by hand (tests) may leave it empty
    const auto* loops = Registry<EventDrivenLawLoops<D>>::instance().find(contacts_.law->name);
    if (!loops || !contacts_.law->hard_sphere) {
        throw std::invalid_argument("EventDrivenEngine: law '" + contacts_.law->name +
                                    "' has no hard-sphere form");
    }
    loop_ = loops->advance;
    ns_ = table.size();
    if (contacts_.species != ns_) {
        throw std::invalid_argument("EventDrivenEngine: the contacts are of another species table");
    }
    for (const auto& s : table.species) {
        mass_.push_back(s.mass);
        diameter_.push_back(s.diameter);
        inertia_.push_back(s.inertia_factor);
    }
    for (double d : diameter_) radius_.push_back(0.5 * d);
    for (int a = 0; a < D; ++a) {
        g_[a] = settings_.gravity[std::size_t(a)];
        if (g_[a] != 0.0) gravity_ = true;
    }
    for (int a = 0; a < 3; ++a) {
        if (a >= D && settings_.gravity[std::size_t(a)] != 0.0)
            throw std::invalid_argument("EventDrivenEngine: gravity has a component beyond the " +
                                        std::to_string(D) + " dimensions of the box");
    }
    rough_ = p_.rotating();
    if (contacts_.rotating && !rough_) {
        throw std::logic_error("EventDrivenEngine: rough contacts need angular velocities");
    }
    pair_collisions_.reset(ns_);

    const std::size_t n = p_.size();
    count_.assign(n, 0);
    last_collision_.assign(n, -kInf);
    events_.reset(n, EventQueue::calendar_for(settings_.queue_layout, n));
    now_ = 0;
    for (std::size_t i = 0; i < n; ++i) now_ = std::max(now_, p_.t[i]);
    set_up_pair_search();
    const std::size_t box_partner = contacts_.wall_named("box");
    for (int a = 0; a < D; ++a) {
        if (!box_.periodic[std::size_t(a)] && box_partner == contacts_.walls.size()) {
            throw std::invalid_argument(
                "EventDrivenEngine: the box has a bounded axis but the contacts have no wall "
                "partner 'box'");
        }
        for (int side = 0; side < 2; ++side) {
            WallSlot& w = walls_[std::size_t(2 * a + side)];
            w.base = side == 0 ? 0.0 : box_.length[a];
            w.simple = g_[a] == 0.0;
            w.partner = box_partner;
        }
    }
    id_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) id_[i] = i;
    sort_every_ = 16 * std::uint64_t(std::max<std::size_t>(n, 64));
    sort_by_cell();
    synchronize();
    predict_all();
    events_.rebuild();
}

template <int D>
double EventDrivenEngine<D>::largest_diameter() const {
    double dmax = 0;
    for (double d : diameter_) dmax = std::max(dmax, d);
    return dmax;
}

template <int D>
void EventDrivenEngine<D>::scan_cells(std::uint32_t i, const std::int32_t* cells, int ncells,
                                      double& best_out, std::int32_t& partner_out) {
    const std::size_t n = cells_.gather(cells, ncells);
    if (!cells_.image_offsets().empty()) {
        scan_gathered_images(i, n, best_out, partner_out);
    } else if (gravity_) {
        scan_gathered<true, true>(i, cells_.candidates(), n, best_out, partner_out);
    } else if (cells_.interior(i)) {
        scan_gathered<false, false>(i, cells_.candidates(), n, best_out, partner_out);
    } else {
        scan_gathered<false, true>(i, cells_.candidates(), n, best_out, partner_out);
    }
}

template <int D>
template <bool Gravity, bool Wraps, class Index>
void EventDrivenEngine<D>::scan_gathered(std::uint32_t i, const Index* candidates, std::size_t n,
                                         double& best_out, std::int32_t& partner_out) const {
    // Locals (not the reference arguments or members) in the loop: writes through references
    // would force the compiler to reload every array pointer after each improvement.
    const Vec<D>* r = p_.r.data();
    const Vec<D>* v = p_.v.data();
    const double* t_local = p_.t.data();
    const std::uint32_t* species = p_.species.data();
    const Index* buf = candidates;
    const double now = now_;
    const Vec<D> ri = r[i];
    const Vec<D> vi = v[i];
    const Vec<D> g = g_;
    const double* radius = radius_.data();
    const double ri_radius = radius[species[i]];
    double best = best_out;
    std::int32_t partner = partner_out;
    // At N >= 10^5 the candidates' lines come from memory. Asking for all of them first lets the
    // misses overlap; the scan's long loop body would otherwise wait for them a few at a time
    // (measured at 3D phi 0.2: +11-45% at N = 10^5, +8% at 10^6, no change at 10^4, where they
    // are in cache; docs/performance.md).
    for (std::size_t m = 0; m < n; ++m) {
        const std::uint32_t j = buf[m];
        __builtin_prefetch(&r[j]);
        __builtin_prefetch(&v[j]);
        __builtin_prefetch(&t_local[j]);
    }
    // Without gravity, two candidates per step (pair_collision_times_two): the same numbers as
    // the one-candidate loop below, which takes the last odd candidate.
    std::size_t first = 0;
    auto scan_two = [&](auto contact) __attribute__((always_inline)) {
        __m128d ri2[D], vi2[D];
        for (int k = 0; k < D; ++k) {
            ri2[std::size_t(k)] = _mm_set1_pd(ri[k]);
            vi2[std::size_t(k)] = _mm_set1_pd(vi[k]);
        }
        const MinimumImageTwo<D> image(box_);
        const __m128d now2 = _mm_set1_pd(now);
        for (; first + 2 <= n; first += 2) {
            const std::uint32_t j0 = buf[first], j1 = buf[first + 1];
            const __m128d dt = _mm_sub_pd(now2, _mm_set_pd(t_local[j1], t_local[j0]));
            __m128d dr[D], dv[D];
            for (std::size_t k = 0; k < std::size_t(D); ++k) {
                const __m128d vj = _mm_set_pd(v[j1][int(k)], v[j0][int(k)]);
                const __m128d rj =
                    _mm_add_pd(_mm_set_pd(r[j1][int(k)], r[j0][int(k)]), _mm_mul_pd(vj, dt));
                const __m128d d = _mm_sub_pd(ri2[k], rj);
                dr[k] = Wraps ? image(d, int(k)) : d;  // Box::separation, two lanes
                dv[k] = _mm_sub_pd(vi2[k], vj);
            }
            const __m128d t =
                pair_collision_times_two<D>(dr, dv, _mm_set_pd(contact(j1), contact(j0)));
            const double t0 = _mm_cvtsd_f64(t), t1 = _mm_cvtsd_f64(_mm_unpackhi_pd(t, t));
            if (j0 != i && t0 < best) {
                best = t0;
                partner = std::int32_t(j0);
            }
            if (j1 != i && t1 < best) {
                best = t1;
                partner = std::int32_t(j1);
            }
        }
    };
    auto scan = [&](auto contact) __attribute__((always_inline)) {
        if constexpr (!Gravity) scan_two(contact);
        for (std::size_t m = first; m < n; ++m) {
            const std::uint32_t j = buf[m];
            if (j == i) continue;
            const double dt = now - t_local[j];
            Vec<D> rj, vj;
            if constexpr (Gravity) {
                // Both fall alike: the relative motion stays linear.
                rj = r[j] + dt * (v[j] + (0.5 * dt) * g);
                vj = v[j] + dt * g;
            } else {
                rj = r[j] + v[j] * dt;
                vj = v[j];
            }
            const Vec<D> dr = Wraps ? box_.separation(ri, rj) : Vec<D>(ri - rj);
            const Vec<D> dv = vi - vj;
            const double t = pair_collision_time_branchless<D>(dr, dv, contact(j));
            if (t < best) {
                best = t;
                partner = std::int32_t(j);
            }
        }
    };
    // One species: the contact distance is a constant and the species array is not read.
    if (ns_ == 1) {
        const double s0 = ri_radius + radius[0];
        scan([s0](std::uint32_t) { return s0; });
    } else {
        scan([ri_radius, radius, species](std::uint32_t j) {
            return ri_radius + radius[species[j]];
        });
    }
    best_out = best;
    partner_out = partner;
}

template <int D>
void EventDrivenEngine<D>::scan_gathered_images(std::uint32_t i, std::size_t n, double& best,
                                                std::int32_t& partner) const {
    const double ri_radius = radius_[p_.species[i]];
    const std::uint32_t* buf = cells_.candidates();
    for (std::size_t m = 0; m < n; ++m) {
        const std::uint32_t j = buf[m];
        if (j == i) continue;
        const double dt = now_ - p_.t[j];
        Vec<D> rj = p_.r[j] + dt * p_.v[j];
        Vec<D> vj = p_.v[j];
        if (gravity_) {
            rj += (0.5 * dt * dt) * g_;
            vj += dt * g_;
        }
        const Vec<D> dr = box_.separation(p_.r[i], rj);
        const Vec<D> dv = p_.v[i] - vj;
        for (const Vec<D>& off : cells_.image_offsets()) {
            const double t =
                pair_collision_time<D>(dr + off, dv, ri_radius + radius_[p_.species[j]], best);
            if (t < best) {
                best = t;
                partner = std::int32_t(j);
            }
        }
    }
}

template <int D>
void EventDrivenEngine<D>::predict(std::uint32_t i) {
    // i must be at now_.
    if (shells_on_) {
        predict_in_shell(i);
        return;
    }
    std::int32_t cells[CellList<D>::kMaxNeighbours];
    const int n = cells_.neighbours(i, cells);
    double best = kInf;
    std::int32_t partner = -1;
    scan_cells(i, cells, n, best, partner);
    schedule(i, best, partner);
}

// With neighbour shells (engine_shells.cpp): a scan of i's list. Here, so that the scan inlines.
template <int D>
void EventDrivenEngine<D>::predict_in_shell(std::uint32_t i) {
    double best = kInf;
    std::int32_t partner = -1;
    const Vec<D>& c = shells_.centre(i);
    bool inside = true;
    for (int a = 0; a < D; ++a) inside &= c[a] >= shell_lo_[a] && c[a] <= shell_hi_[a];
    if (inside) {
        scan_gathered<false, false>(i, shells_.list(i), shells_.size(i), best, partner);
    } else {
        scan_gathered<false, true>(i, shells_.list(i), shells_.size(i), best, partner);
    }
    schedule(i, best, partner);
}

template <int D>
void EventDrivenEngine<D>::predict_after_crossing(std::uint32_t i, int axis, int dir) {
    // The earliest collision with the old neighbourhood is still valid if its partner has not
    // changed since: particles that did change have re-predicted (and hold any earlier collision
    // with i themselves). Only the layer of cells that just became adjacent needs a scan.
    const std::int32_t old = events_.kept_partner(i);
    if (old >= 0 && count_[old] != events_.partner_count(i)) {
        ++counters_.full_rescans_after_crossing;
        predict(i);
        return;
    }
    std::int32_t cells[CellList<D>::kMaxNeighbours];
    const int n = cells_.neighbours(i, cells, axis, dir);
    double best = old >= 0 ? events_.kept_time(i) - now_ : kInf;
    std::int32_t partner = old;
    scan_cells(i, cells, n, best, partner);
    schedule(i, best, partner);
}

template <int D>
void EventDrivenEngine<D>::schedule(std::uint32_t i, double collision, std::int32_t partner) {
    events_.keep_collision(i, now_ + collision, partner, partner >= 0 ? count_[partner] : 0);
    Earliest next{collision, partner >= 0 ? EventKind::collision : EventKind::none, partner};
    if (shells_on_) {
        schedule_in_shell(i, next);
        events_.set(i, now_ + next.time, next.kind, next.code);
        return;
    }
    // Cell crossings, and walls on bounded axes.
    for (int a = 0; a < D; ++a) {
        if (box_.periodic[a] && g_[a] == 0.0) {
            // Periodic axis without gravity: a linear cell crossing, the only event along it.
            // Inline (axis_event's general path, not inlined, cost 10% of the bare dilute gas).
            const double v = p_.v[i][a];
            if (v == 0.0) continue;
            const std::int32_t up = v > 0.0 ? 1 : 0;
            const double t =
                std::max(((cells_.coordinate(i, a) + up) * cells_.width(a) - p_.r[i][a]) / v, 0.0);
            next.consider(t, EventKind::cell, 2 * a + up);
            continue;
        }
        EventKind k = EventKind::none;
        int code = 0;
        const double t = axis_event(i, a, next.time, k, code);
        next.consider(t, k, code);
    }
    events_.set(i, now_ + next.time, next.kind, next.code);
}

template <int D>
double EventDrivenEngine<D>::axis_event(std::uint32_t i, int a, double best, EventKind& kind,
                                        int& code) const {
    const double x = p_.r[i][a];
    const double v = p_.v[i][a];
    const double ga = g_[a];
    const std::int32_t c = cells_.coordinate(i, a);
    const std::int32_t nc = cells_.cells(a);
    const bool periodic = box_.periodic[a];
    const double w = cells_.width(a);
    double t_best = kInf;
    // Cell crossings (never out of the box on a bounded axis: the walls come first).
    if (ga == 0.0) {
        if (v > 0.0 && (periodic || c < nc - 1)) {
            t_best = std::max(((c + 1) * w - x) / v, 0.0);
            kind = EventKind::cell;
            code = 2 * a + 1;
        } else if (v < 0.0 && (periodic || c > 0)) {
            t_best = std::max((c * w - x) / v, 0.0);
            kind = EventKind::cell;
            code = 2 * a;
        }
    } else {
        if (periodic || c < nc - 1) {
            const double t = directed_crossing(x - (c + 1) * w, v, ga, +1);
            if (t < t_best) {
                t_best = t;
                kind = EventKind::cell;
                code = 2 * a + 1;
            }
        }
        if (periodic || c > 0) {
            const double t = directed_crossing(x - c * w, v, ga, -1);
            if (t < t_best) {
                t_best = t;
                kind = EventKind::cell;
                code = 2 * a;
            }
        }
    }
    if (periodic) return t_best;
    return wall_event(i, a, std::min(best, t_best), t_best, kind, code);
}

template <int D>
double EventDrivenEngine<D>::wall_event(std::uint32_t i, int a, double horizon, double t_best,
                                        EventKind& kind, int& code) const {
    const double x = p_.r[i][a];
    const double v = p_.v[i][a];
    const double ga = g_[a];
    const std::int32_t c = cells_.coordinate(i, a);
    const std::int32_t nc = cells_.cells(a);
    const double radius = 0.5 * diameter_[p_.species[i]];
    for (int side = 0; side < 2; ++side) {
        const WallSlot& wall = walls_[std::size_t(2 * a + side)];
        const bool in_reach = side == 0 ? c < wall.layers : c >= nc - wall.layers;
        if (!in_reach) continue;
        double t;
        if (wall.simple) {
            if (side == 0 ? v >= 0.0 : v <= 0.0) continue;
            t = std::max(((side == 0 ? radius : box_.length[a] - radius) - x) / v, 0.0);
        } else {
            const double abs_t =
                next_wall_contact(wall.motion, wall.base, side == 0 ? 1 : -1, x, v, ga, radius,
                                  t_origin_ + now_, t_origin_ + now_ + horizon);
            t = abs_t - (t_origin_ + now_);
        }
        if (t < t_best) {
            t_best = t;
            kind = EventKind::wall;
            code = 2 * a + side;
        }
    }
    return t_best;
}

// The collision record (built only for a subscribed sink): the state before the kernel...
template <int D>
void EventDrivenEngine<D>::record_before(CollisionRecord<D>& rec, std::uint32_t i, std::uint32_t j,
                                         const Vec<D>& n, double alpha, double beta,
                                         double contact) const {
    rec.time = t_origin_ + now_;
    rec.i = id_[i];
    rec.j = id_[j];
    rec.si = p_.species[i];
    rec.sj = p_.species[j];
    rec.n = n;
    rec.ri = p_.r[i];
    copy_velocities(i, j, rec.vi, rec.vj, rec.wi, rec.wj);
    rec.alpha = alpha;
    rec.beta = beta;
    rec.contact_distance = contact;
}

// ...and after it, then handed to the sink.
template <int D>
void EventDrivenEngine<D>::notify(CollisionRecord<D>& rec, std::uint32_t i, std::uint32_t j,
                                  double impulse) {
    copy_velocities(i, j, rec.vi_after, rec.vj_after, rec.wi_after, rec.wj_after);
    rec.impulse = impulse;
    sink_->on_collision(rec);
}

template <int D>
void EventDrivenEngine<D>::cross_cell(std::uint32_t i, int code) {
    move(i);
    const int a = code / 2;
    const int dir = (code % 2) ? 1 : -1;
    const int wrap = cells_.cross(i, a, dir);
    if (wrap > 0) {
        p_.r[i][a] -= box_.length[a];
        ++p_.image[i][std::size_t(a)];
    } else if (wrap < 0) {
        p_.r[i][a] += box_.length[a];
        --p_.image[i][std::size_t(a)];
    }
    ++counters_.cell_crossings;
    if (cells_.cells(a) == 1) {
        // A wrap on a one-cell axis: the images within reach changed (scan_gathered_images).
        predict(i);
    } else {
        predict_after_crossing(i, a, dir);
    }
    events_.commit(i);
}

template <int D>
void EventDrivenEngine<D>::finish_wall_hit(std::uint32_t i, int code, double u, double t_abs,
                                           double before) {
    const int a = code / 2;
    const double inward = code % 2 ? -1.0 : 1.0;
    const WallSlot& w = walls_[std::size_t(code)];
    const double m = mass_[p_.species[i]];
    if (!w.simple) {
        // Resting contact under gravity (or a wall accelerating into the particle): a rebound
        // slower than acc * tc would come back within 2 tc, and at zero speed the same contact
        // would repeat at the same time. The rebound is raised to acc * tc, so a particle resting
        // on a floor makes micro-bounces of period 2 tc (documented in docs/physics.md).
        const double acc_in = -inward * (g_[a] - w.motion.acceleration(t_abs));
        if (acc_in > 0.0) {
            const double lift = acc_in * std::max(settings_.tc, 1e-300);
            if (inward * (p_.v[i][a] - u) < lift) {
                p_.v[i][a] = u + inward * lift;
                ++counters_.wall_lifts;
            }
        }
    }
    wall_impulse_[std::size_t(code)] += m * std::abs(p_.v[i][a] - before);
    last_collision_[i] = now_;
    ++count_[i];
    ++counters_.wall_hits;
    ++wall_hit_count_[std::size_t(code)];
    repredict(i);
}

template <int D>
void EventDrivenEngine<D>::set_wall(int axis, int side, const WallMotion& motion,
                                    std::size_t partner, WallReflection<D>* reflection) {
    if (axis < 0 || axis >= D || box_.periodic[std::size_t(axis)]) {
        throw std::invalid_argument("set_wall: walls need a bounded (non-periodic) axis");
    }
    if (!reflection && partner >= contacts_.walls.size()) {
        throw std::invalid_argument("set_wall: no such wall partner");
    }
    WallSlot& w = walls_[std::size_t(2 * axis + side)];
    w.reflection = reflection;
    w.partner = partner;
    w.motion = motion;
    const double reach = motion.reach();
    w.base = side == 0 ? reach : box_.length[axis] - reach;
    w.simple = motion.is_static() && g_[axis] == 0.0;
    // A particle centre in contact lies within 2 reach + radius of the box boundary (and, with
    // neighbour shells, the cell is that of its shell's centre, up to skin / 2 further).
    const double dmax = largest_diameter();
    const double skin = shells_on_ ? shells_.skin() : 0.0;
    const auto layers = static_cast<std::int32_t>(std::floor(
                            (2.0 * reach + 0.5 * dmax + 0.5 * skin) / cells_.width(axis))) +
                        1;
    w.layers = std::min(layers, cells_.cells(axis));
    if (2.0 * reach + dmax > box_.length[axis]) {
        throw std::invalid_argument("set_wall: the wall's excursion leaves no room for particles");
    }
    // Events already scheduled ignore this wall: predict again.
    if (p_.size() > 0) {
        synchronize();
        for (std::uint32_t i = 0; i < p_.size(); ++i) predict(i);
        events_.rebuild();
    }
}

template class EventDrivenEngine<2>;
template class EventDrivenEngine<3>;

}  // namespace gran
