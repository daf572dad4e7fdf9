#include "libgran/engines/event_driven/engine.hpp"

#include "libgran/core/registry.hpp"

#include <stdexcept>

namespace gran {

template <int D>
EventDrivenEngine<D>::EventDrivenEngine(const Box<D>& box, const SpeciesTable& table,
                                        const ContactTable& contacts, Particles<D> particles,
                                        EngineSettings settings)
    : box_(box), p_(std::move(particles)), settings_(settings), contacts_(contacts) {
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
    sigma_pair_.resize(ns_ * ns_);
    for (std::size_t a = 0; a < ns_; ++a) {
        for (std::size_t b = 0; b < ns_; ++b)
            sigma_pair_[a * ns_ + b] = 0.5 * (diameter_[a] + diameter_[b]);
    }
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
    pair_collisions_.assign(ns_ * ns_, 0);

    const std::size_t n = p_.size();
    count_.assign(n, 0);
    last_collision_.assign(n, -kInf);
    ev_time_.assign(n, kInf);
    ev_partner_.assign(n, -1);
    ev_count_.assign(n, 0);
    coll_time_.assign(n, kInf);
    coll_partner_.assign(n, -1);
    ev_kind_.assign(n, kNone);
    now_ = 0;
    for (std::size_t i = 0; i < n; ++i) now_ = std::max(now_, p_.t[i]);
    build_cells();
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
    queue_.reset(n);
    synchronize();
    for (std::uint32_t i = 0; i < n; ++i) predict(i);
    queue_.rebuild([this](std::uint32_t i) { return ev_time_[i]; });
}

template <int D>
std::int32_t EventDrivenEngine<D>::cell_id(const std::array<std::int32_t, D>& cc) const {
    std::int32_t id = 0;
    for (int a = D - 1; a >= 0; --a) id = id * ncell_[a] + cc[a];
    return id;
}

template <int D>
void EventDrivenEngine<D>::build_cells() {
    double dmax = 0;
    for (double d : diameter_) dmax = std::max(dmax, d);
    std::int64_t total = 1;
    for (int a = 0; a < D; ++a) {
        auto nc = static_cast<std::int64_t>(std::floor(box_.length[a] / dmax));
        // Periodic axes need >= 4 cells: then two particles in adjacent cells are less than half
        // a period apart, so the minimum image is the image through which they can meet before
        // one of them crosses a cell. With 3 cells, particles in cells 0 and 2 (adjacent through
        // the wrap) may recede in the minimum image and meet through the other one without
        // either crossing a cell: collisions were missed (overlaps of up to 35% of a diameter,
        // tests/extremes/test_mass_and_size_ratio.cpp). Fewer means one cell (below).
        if (nc < 1 || (box_.periodic[a] && nc < 4)) nc = 1;
        ncell_[a] = static_cast<std::int32_t>(nc);
        total *= nc;
    }
    // Very dilute systems: cap the cell count (memory, empty-cell scans) at ~8 cells per particle.
    const std::int64_t cap = std::max<std::int64_t>(1 << 16, 8 * std::int64_t(p_.size()));
    while (total > cap) {
        int a_max = 0;
        for (int a = 1; a < D; ++a) {
            if (ncell_[a] > ncell_[a_max]) a_max = a;
        }
        if (ncell_[a_max] <= 4) break;
        total /= ncell_[a_max];
        ncell_[a_max] = std::max(ncell_[a_max] / 2, 4);
        total *= ncell_[a_max];
    }
    for (int a = 0; a < D; ++a) cell_width_[a] = box_.length[a] / ncell_[a];
    image_offsets_.clear();
    bool wrapped = false;
    for (int a = 0; a < D; ++a) wrapped = wrapped || (box_.periodic[a] && ncell_[a] == 1);
    if (wrapped) {
        std::array<int, D> k;
        k.fill(-2);
        while (true) {
            Vec<D> off = Vec<D>::Zero();
            bool ok = true;
            for (int a = 0; a < D; ++a) {
                const bool w = box_.periodic[a] && ncell_[a] == 1;
                if (!w && k[a] != 0) ok = false;
                off[a] = k[a] * box_.length[a];
            }
            if (ok) image_offsets_.push_back(off);
            int a = 0;
            while (a < D && ++k[a] > 2) k[a++] = -2;
            if (a == D) break;
        }
    }

    slots_ = double(p_.size()) >= 0.25 * double(total);
    // At most 4 equal disks (8 spheres) have centres in a cell one diameter wide; smaller species
    // may need more, and grow_cells() doubles the capacity then.
    cell_capacity_ = D == 2 ? 4 : 8;
    if (slots_) {
        cell_count_.assign(std::size_t(total), 0);
        cell_ids_.assign(std::size_t(total) * std::size_t(cell_capacity_), 0);
    } else {
        head_.assign(std::size_t(total), -1);
    }
    gather_.assign(p_.size() + 28 * std::size_t(cell_capacity_), 0);
    const std::size_t n = p_.size();
    cc_.assign(n, {});
    cell_of_.assign(n, -1);
    slot_.assign(n, 0);
    next_.assign(n, -1);
    prev_.assign(n, -1);
    for (std::uint32_t i = 0; i < n; ++i) {
        std::array<std::int32_t, D> cc;
        for (int a = 0; a < D; ++a) {
            auto k = static_cast<std::int32_t>(std::floor(p_.r[i][a] / cell_width_[a]));
            cc[a] = std::clamp(k, 0, ncell_[a] - 1);
        }
        cc_[i] = cc;
        cell_insert(i, cell_id(cc));
    }
}

template <int D>
void EventDrivenEngine<D>::cell_insert(std::uint32_t i, std::int32_t c) {
    cell_of_[i] = c;
    if (!slots_) {
        prev_[i] = -1;
        next_[i] = head_[c];
        if (head_[c] >= 0) prev_[head_[c]] = static_cast<std::int32_t>(i);
        head_[c] = static_cast<std::int32_t>(i);
        return;
    }
    if (cell_count_[c] == cell_capacity_) grow_cells();
    const std::int32_t k = cell_count_[c]++;
    slot_[i] = k;
    cell_ids_[std::size_t(c) * cell_capacity_ + k] = i;
}

template <int D>
void EventDrivenEngine<D>::grow_cells() {
    const std::int32_t cap = 2 * cell_capacity_;
    std::vector<std::uint32_t> ids(cell_count_.size() * std::size_t(cap), 0);
    for (std::size_t c = 0; c < cell_count_.size(); ++c) {
        std::copy_n(&cell_ids_[c * cell_capacity_], cell_count_[c], &ids[c * cap]);
    }
    cell_ids_.swap(ids);
    cell_capacity_ = cap;
    gather_.assign(p_.size() + 28 * std::size_t(cap), 0);
}

template <int D>
void EventDrivenEngine<D>::cell_remove(std::uint32_t i) {
    const std::int32_t c = cell_of_[i];
    if (!slots_) {
        if (prev_[i] >= 0) {
            next_[prev_[i]] = next_[i];
        } else {
            head_[c] = next_[i];
        }
        if (next_[i] >= 0) prev_[next_[i]] = prev_[i];
        return;
    }
    std::uint32_t* cell = &cell_ids_[std::size_t(c) * cell_capacity_];
    const std::int32_t last = --cell_count_[c];
    const std::int32_t k = slot_[i];
    if (k != last) {
        cell[k] = cell[last];
        slot_[cell[k]] = k;
    }
}

template <int D>
int EventDrivenEngine<D>::neighbour_cells(std::uint32_t i, std::int32_t* out, int layer_axis,
                                          int layer_dir) const {
    // Cell ids from the cell coordinates (a per-cell table falls out of cache at N = 1e5). Per
    // axis, the three candidate coordinates (offsets -1, 0, +1) and whether each is in the
    // neighbourhood; then every combination is written and the write position advanced only for
    // valid ones, with fixed trip counts. The fixed shape lets the compiler keep the per-axis
    // values in registers: the earlier variable-length lists were stored element by element and
    // read back with one vector load, a failed store-to-load forwarding that cost ~8% of all
    // cycles of the bare 2D gas at phi = 0.5 (perf annotate; gran_bench_features).
    std::int32_t ax[D][3];
    int ok[D][3];
    std::int32_t stride = 1;
    for (int a = 0; a < D; ++a) {
        const std::int32_t nc = ncell_[a];
        for (int o = 0; o < 3; ++o) {
            std::int32_t c = cc_[i][a] + o - 1;
            bool valid = true;
            if (nc == 1) {
                // One cell along this axis: a crossing leaves the neighbourhood unchanged.
                valid = o == 1 && a != layer_axis;
                c = 0;
            } else {
                if (a == layer_axis && o - 1 != layer_dir) valid = false;
                if (c < 0 || c >= nc) {
                    if (!box_.periodic[a]) valid = false;
                    c = c < 0 ? c + nc : c - nc;
                }
            }
            ax[a][o] = c * stride;
            ok[a][o] = valid ? 1 : 0;
        }
        stride *= nc;
    }
    int n = 0;
    if constexpr (D == 2) {
        for (int y = 0; y < 3; ++y) {
            for (int x = 0; x < 3; ++x) {
                out[n] = ax[1][y] + ax[0][x];
                n += ok[1][y] & ok[0][x];
            }
        }
    } else {
        for (int z = 0; z < 3; ++z) {
            for (int y = 0; y < 3; ++y) {
                for (int x = 0; x < 3; ++x) {
                    out[n] = ax[2][z] + ax[1][y] + ax[0][x];
                    n += ok[2][z] & ok[1][y] & ok[0][x];
                }
            }
        }
    }
    return n;
}

template <int D>
void EventDrivenEngine<D>::scan_cells(std::uint32_t i, const std::int32_t* cells, int ncells,
                                      double& best_out, std::int32_t& partner_out) const {
    // Gather the candidates (see the cell layouts in the header), then scan them.
    std::uint32_t* buf = gather_.data();
    std::size_t n = 0;
    if (slots_) {
        const std::size_t cap = std::size_t(cell_capacity_);
        for (int k = 0; k < ncells; ++k) {
            const std::size_t c = std::size_t(cells[k]);
            std::copy_n(&cell_ids_[c * cap], cap, buf + n);
            n += std::size_t(cell_count_[c]);
        }
    } else {
        for (int k = 0; k < ncells; ++k) {
            for (std::int32_t j = head_[cells[k]]; j >= 0; j = next_[j])
                buf[n++] = std::uint32_t(j);
        }
    }
    if (!image_offsets_.empty()) {
        scan_gathered_images(i, n, best_out, partner_out);
    } else if (gravity_) {
        scan_gathered<true>(i, n, best_out, partner_out);
    } else {
        scan_gathered<false>(i, n, best_out, partner_out);
    }
}

template <int D>
template <bool Gravity>
void EventDrivenEngine<D>::scan_gathered(std::uint32_t i, std::size_t n, double& best_out,
                                         std::int32_t& partner_out) const {
    // Locals (not the reference arguments or members) in the loop: writes through references
    // would force the compiler to reload every array pointer after each improvement.
    const Vec<D>* r = p_.r.data();
    const Vec<D>* v = p_.v.data();
    const double* t_local = p_.t.data();
    const std::uint32_t* species = p_.species.data();
    const std::uint32_t* buf = gather_.data();
    const double now = now_;
    const Vec<D> ri = r[i];
    const Vec<D> vi = v[i];
    const Vec<D> g = g_;
    const double* sig = &sigma_pair_[species[i] * ns_];
    double best = best_out;
    std::int32_t partner = partner_out;
    auto scan = [&](auto contact) {
        for (std::size_t m = 0; m < n; ++m) {
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
            const Vec<D> dr = box_.separation(ri, rj);
            const Vec<D> dv = vi - vj;
            const double t = pair_collision_time<D>(dr, dv, contact(j), best);
            if (t < best) {
                best = t;
                partner = std::int32_t(j);
            }
        }
    };
    // One species: the contact distance is a constant and the species array is not read.
    if (ns_ == 1) {
        const double s0 = sig[0];
        scan([s0](std::uint32_t) { return s0; });
    } else {
        scan([sig, species](std::uint32_t j) { return sig[species[j]]; });
    }
    best_out = best;
    partner_out = partner;
}

template <int D>
void EventDrivenEngine<D>::scan_gathered_images(std::uint32_t i, std::size_t n, double& best,
                                                std::int32_t& partner) const {
    const double* sig = &sigma_pair_[p_.species[i] * ns_];
    for (std::size_t m = 0; m < n; ++m) {
        const std::uint32_t j = gather_[m];
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
        for (const Vec<D>& off : image_offsets_) {
            const double t = pair_collision_time<D>(dr + off, dv, sig[p_.species[j]], best);
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
    std::int32_t cells[27];
    const int n = neighbour_cells(i, cells);
    double best = kInf;
    std::int32_t partner = -1;
    scan_cells(i, cells, n, best, partner);
    schedule(i, best, partner);
}

template <int D>
void EventDrivenEngine<D>::predict_after_crossing(std::uint32_t i, int axis, int dir) {
    // The earliest collision with the old neighbourhood is still valid if its partner has not
    // changed since: particles that did change have re-predicted (and hold any earlier collision
    // with i themselves). Only the layer of cells that just became adjacent needs a scan.
    const std::int32_t old = coll_partner_[i];
    if (old >= 0 && count_[old] != ev_count_[i]) {
        ++counters_.full_rescans_after_crossing;
        predict(i);
        return;
    }
    std::int32_t cells[27];  // neighbour_cells writes up to 27 entries (returns the valid ones)
    const int n = neighbour_cells(i, cells, axis, dir);
    double best = old >= 0 ? coll_time_[i] - now_ : kInf;
    std::int32_t partner = old;
    scan_cells(i, cells, n, best, partner);
    schedule(i, best, partner);
}

template <int D>
void EventDrivenEngine<D>::schedule(std::uint32_t i, double collision, std::int32_t partner) {
    coll_time_[i] = now_ + collision;
    coll_partner_[i] = partner;
    if (partner >= 0) ev_count_[i] = count_[partner];
    double best = collision;
    std::uint8_t kind = partner >= 0 ? kCollision : kNone;
    std::int32_t code_best = partner;
    // Cell crossings, and walls on bounded axes.
    for (int a = 0; a < D; ++a) {
        if (box_.periodic[a] && g_[a] == 0.0) {
            // Periodic axis without gravity: a linear cell crossing, the only event along it.
            // Inline (axis_event's general path, not inlined, cost 10% of the bare dilute gas).
            const double v = p_.v[i][a];
            if (v == 0.0) continue;
            const std::int32_t up = v > 0.0 ? 1 : 0;
            const double t = std::max(((cc_[i][a] + up) * cell_width_[a] - p_.r[i][a]) / v, 0.0);
            if (t < best) {
                best = t;
                kind = kCell;
                code_best = 2 * a + up;
            }
            continue;
        }
        std::uint8_t k = kNone;
        int code = 0;
        const double t = axis_event(i, a, best, k, code);
        if (t < best) {
            best = t;
            kind = k;
            code_best = code;
        }
    }
    ev_time_[i] = now_ + best;
    ev_kind_[i] = kind;
    ev_partner_[i] = code_best;
}

namespace {

// Earliest s >= 0 at which x(s) = c + v s + a s^2 / 2 (c: position relative to a cell boundary)
// crosses 0 moving in direction dir (+1 up, -1 down), or +inf. Direction-aware so a particle that
// has just crossed a boundary (and sits on it, either side by round-off) is never sent back at
// once: the roots are labelled by the velocity v + a s = +-sqrt(v^2 - 2 a c) they cross with. Only
// a particle already past the boundary and moving (or, at rest, accelerating) on crosses now.
inline double directed_crossing(double c, double v, double a, int dir) {
    if (dir * c >= 0.0 && (dir * v > 0.0 || (v == 0.0 && dir * a > 0.0))) return 0.0;
    if (a == 0.0) return dir * v > 0.0 ? std::max(-c / v, 0.0) : kInf;
    const double disc = v * v - 2.0 * a * c;
    if (!(disc > 0.0)) return kInf;
    const double sq = std::sqrt(disc);
    // Root crossing upward: v + a s = +sq; downward: v + a s = -sq (cancellation-free forms).
    double s;
    if (dir > 0) {
        s = v > 0.0 ? -2.0 * c / (sq + v) : (sq - v) / a;
    } else {
        s = v < 0.0 ? 2.0 * c / (sq - v) : -(v + sq) / a;
    }
    return s >= 0.0 ? s : kInf;
}

}  // namespace

template <int D>
double EventDrivenEngine<D>::axis_event(std::uint32_t i, int a, double best, std::uint8_t& kind,
                                        int& code) const {
    const double x = p_.r[i][a];
    const double v = p_.v[i][a];
    const double ga = g_[a];
    const std::int32_t c = cc_[i][a];
    const std::int32_t nc = ncell_[a];
    const bool periodic = box_.periodic[a];
    const double w = cell_width_[a];
    double t_best = kInf;
    // Cell crossings (never out of the box on a bounded axis: the walls come first).
    if (ga == 0.0) {
        if (v > 0.0 && (periodic || c < nc - 1)) {
            t_best = std::max(((c + 1) * w - x) / v, 0.0);
            kind = kCell;
            code = 2 * a + 1;
        } else if (v < 0.0 && (periodic || c > 0)) {
            t_best = std::max((c * w - x) / v, 0.0);
            kind = kCell;
            code = 2 * a;
        }
    } else {
        if (periodic || c < nc - 1) {
            const double t = directed_crossing(x - (c + 1) * w, v, ga, +1);
            if (t < t_best) {
                t_best = t;
                kind = kCell;
                code = 2 * a + 1;
            }
        }
        if (periodic || c > 0) {
            const double t = directed_crossing(x - c * w, v, ga, -1);
            if (t < t_best) {
                t_best = t;
                kind = kCell;
                code = 2 * a;
            }
        }
    }
    if (periodic) return t_best;
    const double radius = 0.5 * diameter_[p_.species[i]];
    const double horizon = std::min(best, t_best);
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
            kind = kWall;
            code = 2 * a + side;
        }
    }
    return t_best;
}

template <int D>
void EventDrivenEngine<D>::cross_cell(std::uint32_t i, int code) {
    move(i);
    const int a = code / 2;
    const int dir = (code % 2) ? 1 : -1;
    cell_remove(i);
    auto& c = cc_[i][a];
    c += dir;
    if (c >= ncell_[a]) {
        c = 0;
        p_.r[i][a] -= box_.length[a];
    } else if (c < 0) {
        c = ncell_[a] - 1;
        p_.r[i][a] += box_.length[a];
    }
    cell_insert(i, cell_id(cc_[i]));
    ++counters_.cell_crossings;
    if (ncell_[a] == 1) {
        predict(
            i);  // a wrap on a one-cell axis: images within reach changed (scan_gathered_images)
    } else {
        predict_after_crossing(i, a, dir);
    }
    queue_.update(i, ev_time_[i]);
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
    predict(i);
    queue_.update(i, ev_time_[i]);
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
    // A particle centre in contact lies within 2 reach + radius of the box boundary.
    double dmax = 0;
    for (double d : diameter_) dmax = std::max(dmax, d);
    const auto layers =
        static_cast<std::int32_t>(std::floor((2.0 * reach + 0.5 * dmax) / cell_width_[axis])) + 1;
    w.layers = std::min(layers, ncell_[axis]);
    if (2.0 * reach + dmax > box_.length[axis]) {
        throw std::invalid_argument("set_wall: the wall's excursion leaves no room for particles");
    }
    // Events already scheduled ignore this wall: predict again.
    if (p_.size() > 0) {
        synchronize();
        for (std::uint32_t i = 0; i < p_.size(); ++i) predict(i);
        queue_.rebuild([this](std::uint32_t k) { return ev_time_[k]; });
    }
}

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
        ev_time_[i] -= shift;
        coll_time_[i] -= shift;
        last_collision_[i] -= shift;
    }
    t_origin_ += shift;
    now_ = 0.0;
    queue_.rebuild([this](std::uint32_t k) { return ev_time_[k]; });
}

template <int D>
void EventDrivenEngine<D>::synchronize() {
    for (std::uint32_t i = 0; i < p_.size(); ++i) move(i);
}

template <int D>
void EventDrivenEngine<D>::velocities_changed() {
    synchronize();
    for (std::uint32_t i = 0; i < p_.size(); ++i) ++count_[i];
    for (std::uint32_t i = 0; i < p_.size(); ++i) predict(i);
    queue_.rebuild([this](std::uint32_t i) { return ev_time_[i]; });
    ++counters_.full_reschedules;
}

namespace {
template <class T>
void permute(std::vector<T>& v, const std::vector<std::uint32_t>& order) {
    if (v.empty()) return;
    std::vector<T> old(std::move(v));
    v.resize(old.size());
    for (std::size_t k = 0; k < order.size(); ++k) v[k] = old[order[k]];
}
}  // namespace

template <int D>
void EventDrivenEngine<D>::sort_by_cell() {
    // Counting sort of particles by cell: neighbours in space become neighbours in memory, so a
    // cell scan touches few cache lines (the storage stays structure-of-arrays).
    const std::size_t n = p_.size();
    const std::size_t ncells = slots_ ? cell_count_.size() : head_.size();
    std::vector<std::uint32_t> start(ncells + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++start[std::size_t(cell_of_[i]) + 1];
    for (std::size_t c = 0; c < ncells; ++c) start[c + 1] += start[c];
    std::vector<std::uint32_t> order(n), inv(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t k = start[std::size_t(cell_of_[i])]++;
        order[k] = i;
        inv[i] = k;
    }
    permute(p_.r, order);
    permute(p_.v, order);
    permute(p_.t, order);
    permute(p_.species, order);
    permute(p_.w, order);
    permute(id_, order);
    permute(count_, order);
    permute(last_collision_, order);
    permute(ev_time_, order);
    permute(ev_partner_, order);
    permute(ev_count_, order);
    permute(ev_kind_, order);
    permute(coll_time_, order);
    permute(coll_partner_, order);
    permute(cc_, order);
    permute(cell_of_, order);
    for (std::size_t k = 0; k < n; ++k) {
        if (ev_kind_[k] == kCollision)
            ev_partner_[k] = std::int32_t(inv[std::size_t(ev_partner_[k])]);
        if (coll_partner_[k] >= 0)
            coll_partner_[k] = std::int32_t(inv[std::size_t(coll_partner_[k])]);
    }
    // Rebuild the cell lists so each list runs in increasing storage order.
    std::fill(cell_count_.begin(), cell_count_.end(), 0);
    std::fill(head_.begin(), head_.end(), -1);
    for (std::size_t k = 0; k < n; ++k) cell_insert(std::uint32_t(k), cell_of_[k]);
    ++counters_.sorts;
}

template class EventDrivenEngine<2>;
template class EventDrivenEngine<3>;

}  // namespace gran
