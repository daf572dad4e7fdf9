#include "bench/minimal_event_driven.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gran::bench {

namespace {
constexpr double kInfTime = 1e300;
}

template <int D>
MinimalEventDriven<D>::MinimalEventDriven(double box, std::vector<double> r, std::vector<double> v)
    : L_(box) {
    const std::size_t n = r.size() / D;
    if (r.size() != n * D || v.size() != n * D) throw std::invalid_argument("r, v: n * D values");
    nc_ = static_cast<int>(std::floor(L_));  // cells at least one diameter wide
    if (nc_ < 3) throw std::invalid_argument("box shorter than three diameters");
    w_ = L_ / nc_;
    std::size_t ncells = 1;
    for (int a = 0; a < D; ++a) ncells *= std::size_t(nc_);
    head_.assign(ncells, -1);
    p_.resize(n);
    cell_.assign(n, -1);
    cc_.assign(n * D, 0);
    next_.assign(n, -1);
    prev_.assign(n, -1);
    count_.assign(n, 0);
    ev_t_.assign(n, kInfTime);
    ev_partner_.assign(n, -1);
    ev_count_.assign(n, 0);
    ev_axis_.assign(n, -1);
    best_t_.assign(n, kInfTime);
    best_j_.assign(n, -1);
    best_count_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        std::int32_t c = 0;
        for (int a = 0; a < D; ++a) {
            p_[i].r[a] = r[i * D + std::size_t(a)];
            p_[i].v[a] = v[i * D + std::size_t(a)];
            int k = static_cast<int>(std::floor(p_[i].r[a] / w_));
            k = k < 0 ? 0 : (k >= nc_ ? nc_ - 1 : k);
            cc_[i * D + std::size_t(a)] = k;
            c = c * nc_ + k;
        }
        p_[i].t = 0;
        insert(std::uint32_t(i), c);
    }
    heap_.resize(n);
    pos_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        heap_[i] = {kInfTime, i};
        pos_[i] = i;
    }
    for (std::uint32_t i = 0; i < n; ++i) predict(i, -1, 0);
}

template <int D>
void MinimalEventDriven<D>::insert(std::uint32_t i, std::int32_t c) {
    cell_[i] = c;
    prev_[i] = -1;
    next_[i] = head_[std::size_t(c)];
    if (next_[i] >= 0) prev_[std::size_t(next_[i])] = std::int32_t(i);
    head_[std::size_t(c)] = std::int32_t(i);
}

template <int D>
void MinimalEventDriven<D>::remove(std::uint32_t i) {
    if (prev_[i] >= 0) {
        next_[std::size_t(prev_[i])] = next_[i];
    } else {
        head_[std::size_t(cell_[i])] = next_[i];
    }
    if (next_[i] >= 0) prev_[std::size_t(next_[i])] = prev_[i];
}

template <int D>
void MinimalEventDriven<D>::heap_update(std::uint32_t id, double t) {
    std::size_t k = pos_[id];
    const double old = heap_[k].t;
    const Entry e{t, id};
    if (t < old) {
        while (k > 0) {
            const std::size_t parent = (k - 1) / 4;
            if (!(t < heap_[parent].t)) break;
            heap_[k] = heap_[parent];
            pos_[heap_[k].id] = std::uint32_t(k);
            k = parent;
        }
        heap_[k] = e;
        pos_[id] = std::uint32_t(k);
    } else {
        heap_[k] = e;
        sift_down(k);
    }
}

template <int D>
void MinimalEventDriven<D>::sift_down(std::size_t k) {
    const Entry e = heap_[k];
    const std::size_t n = heap_.size();
    while (true) {
        const std::size_t first = 4 * k + 1;
        if (first >= n) break;
        // Smallest of up to four children, its time kept in a register (no dependent reload).
        std::size_t best = first;
        double tb = heap_[first].t;
        const std::size_t last = first + 4 < n ? first + 4 : n;
        for (std::size_t c = first + 1; c < last; ++c) {
            const double tc = heap_[c].t;
            best = tc < tb ? c : best;
            tb = tc < tb ? tc : tb;
        }
        if (!(tb < e.t)) break;
        heap_[k] = heap_[best];
        pos_[heap_[k].id] = std::uint32_t(k);
        k = best;
    }
    heap_[k] = e;
    pos_[e.id] = std::uint32_t(k);
}

template <int D>
void MinimalEventDriven<D>::predict(std::uint32_t i, int layer_axis, int layer_dir) {
    P& pi = p_[i];
    {
        const double dt = now_ - pi.t;
        for (int a = 0; a < D; ++a) pi.r[a] += pi.v[a] * dt;
        pi.t = now_;
    }
    const std::int32_t* ci = &cc_[std::size_t(i) * D];

    // Earliest collision: keep the previous scan's best after a crossing if still valid.
    double best = kInfTime;  // absolute time
    std::int32_t partner = -1;
    bool full = layer_axis < 0;
    if (!full) {
        const std::int32_t j = best_j_[i];
        if (j >= 0 && count_[std::size_t(j)] == best_count_[i]) {
            best = best_t_[i];
            partner = j;
        } else {
            full = true;
        }
    }
    int off[D];
    for (int a = 0; a < D; ++a) off[a] = -1;
    constexpr int ncand = D == 2 ? 9 : 27;
    for (int k = 0; k < ncand; ++k) {
        // Offsets in {-1, 0, 1}^D, odometer order.
        if (k > 0) {
            for (int a = D - 1; a >= 0; --a) {
                if (++off[a] <= 1) break;
                off[a] = -1;
            }
        }
        if (!full && off[layer_axis] != layer_dir) continue;
        std::int32_t c = 0;
        double shift[D];
        for (int a = 0; a < D; ++a) {
            int q = ci[a] + off[a];
            shift[a] = 0;
            if (q < 0) {
                q += nc_;
                shift[a] = -L_;
            } else if (q >= nc_) {
                q -= nc_;
                shift[a] = L_;
            }
            c = c * nc_ + q;
        }
        for (std::int32_t j = head_[std::size_t(c)]; j >= 0; j = next_[std::size_t(j)]) {
            if (std::uint32_t(j) == i) continue;
            const P& pj = p_[std::size_t(j)];
            const double dtj = now_ - pj.t;
            double dr[D], dv[D];
            double b = 0, r2 = 0, v2 = 0;
            for (int a = 0; a < D; ++a) {
                dr[a] = pi.r[a] - (pj.r[a] + pj.v[a] * dtj + shift[a]);
                dv[a] = pi.v[a] - pj.v[a];
                b += dr[a] * dv[a];
            }
            if (b >= 0) continue;
            for (int a = 0; a < D; ++a) r2 += dr[a] * dr[a];
            const double cq = r2 - 1.0;
            double t;
            if (cq <= 0) {
                t = 0;  // approaching and (by round-off) overlapping: collide now
            } else {
                if (cq > -2.0 * b * (best - now_)) continue;  // root >= c / (-2b): cannot win
                for (int a = 0; a < D; ++a) v2 += dv[a] * dv[a];
                const double disc = b * b - v2 * cq;
                if (disc <= 0) continue;
                t = cq / (-b + std::sqrt(disc));
            }
            if (now_ + t < best) {
                best = now_ + t;
                partner = j;
            }
        }
    }
    best_t_[i] = best;
    best_j_[i] = partner;
    best_count_[i] = partner >= 0 ? count_[std::size_t(partner)] : 0;

    // Next cell crossing.
    double tcross = kInfTime;
    int axis = -1;
    for (int a = 0; a < D; ++a) {
        const double va = pi.v[a];
        if (va == 0) continue;
        const double wall = va > 0 ? (ci[a] + 1) * w_ : ci[a] * w_;
        double t = (wall - pi.r[a]) / va;
        t = t < 0 ? 0 : t;
        if (t < tcross) {
            tcross = t;
            axis = a;
        }
    }
    tcross += now_;
    if (partner >= 0 && best <= tcross) {
        ev_t_[i] = best;
        ev_partner_[i] = partner;
        ev_count_[i] = best_count_[i];
        ev_axis_[i] = -1;
    } else {
        ev_t_[i] = tcross;
        ev_partner_[i] = -1;
        ev_axis_[i] = std::int8_t(axis);
    }
    heap_update(i, ev_t_[i]);
}

template <int D>
void MinimalEventDriven<D>::collide(std::uint32_t i, std::uint32_t j) {
    P& pi = p_[i];
    P& pj = p_[j];
    const double dti = now_ - pi.t, dtj = now_ - pj.t;
    double dr[D], dv[D];
    double b = 0, r2 = 0;
    for (int a = 0; a < D; ++a) {
        pi.r[a] += pi.v[a] * dti;
        pj.r[a] += pj.v[a] * dtj;
        double d = pi.r[a] - pj.r[a];
        d = d > 0.5 * L_ ? d - L_ : (d < -0.5 * L_ ? d + L_ : d);  // minimum image
        dr[a] = d;
        dv[a] = pi.v[a] - pj.v[a];
        b += dr[a] * dv[a];
        r2 += d * d;
    }
    pi.t = now_;
    pj.t = now_;
    if (r2 < 1.0 - 1e-9) ++overlaps_;
    // Equal masses, elastic, smooth: exchange the normal components of the velocities.
    const double f = b / r2;
    for (int a = 0; a < D; ++a) {
        pi.v[a] -= f * dr[a];
        pj.v[a] += f * dr[a];
    }
    ++count_[i];
    ++count_[j];
    ++collisions_;
}

template <int D>
void MinimalEventDriven<D>::cross(std::uint32_t i) {
    P& pi = p_[i];
    const double dt = now_ - pi.t;
    for (int a = 0; a < D; ++a) pi.r[a] += pi.v[a] * dt;
    pi.t = now_;
    const int axis = ev_axis_[i];
    const int dir = pi.v[axis] > 0 ? 1 : -1;
    std::int32_t* ci = &cc_[std::size_t(i) * D];
    int q = ci[axis] + dir;
    if (q < 0) {
        q += nc_;
        pi.r[axis] += L_;
    } else if (q >= nc_) {
        q -= nc_;
        pi.r[axis] -= L_;
    }
    ci[axis] = q;
    std::int32_t c = 0;
    for (int a = 0; a < D; ++a) c = c * nc_ + ci[a];
    remove(i);
    insert(i, c);
    predict(i, axis, dir);
}

template <int D>
void MinimalEventDriven<D>::sort_by_cell() {
    // Counting sort of the particles by cell, then every per-particle array permuted, partner
    // indices renamed, cell lists and heap rebuilt.
    const std::size_t n = p_.size();
    std::vector<std::uint32_t> start(head_.size() + 1, 0), order(n), inv(n);
    for (std::size_t i = 0; i < n; ++i) ++start[std::size_t(cell_[i]) + 1];
    for (std::size_t c = 0; c + 1 < start.size(); ++c) start[c + 1] += start[c];
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t k = start[std::size_t(cell_[i])]++;
        order[k] = i;
        inv[i] = k;
    }
    auto permute = [&](auto& a, std::size_t stride) {
        auto old = a;
        for (std::size_t k = 0; k < n; ++k)
            for (std::size_t s = 0; s < stride; ++s) a[k * stride + s] = old[order[k] * stride + s];
    };
    permute(p_, 1);
    permute(cell_, 1);
    permute(cc_, D);
    permute(count_, 1);
    permute(ev_t_, 1);
    permute(ev_partner_, 1);
    permute(ev_count_, 1);
    permute(ev_axis_, 1);
    permute(best_t_, 1);
    permute(best_j_, 1);
    permute(best_count_, 1);
    for (std::size_t k = 0; k < n; ++k) {
        if (ev_partner_[k] >= 0) ev_partner_[k] = std::int32_t(inv[std::size_t(ev_partner_[k])]);
        if (best_j_[k] >= 0) best_j_[k] = std::int32_t(inv[std::size_t(best_j_[k])]);
    }
    std::fill(head_.begin(), head_.end(), -1);
    for (std::size_t k = n; k-- > 0;) insert(std::uint32_t(k), cell_[k]);
    for (std::uint32_t k = 0; k < n; ++k) {
        heap_[k] = {ev_t_[k], k};
        pos_[k] = k;
    }
    for (std::size_t k = n / 4 + 1; k-- > 0;) sift_down(k);
}

template <int D>
void MinimalEventDriven<D>::run_until(std::uint64_t collision_target) {
    while (collisions_ < collision_target) {
        if (events_ >= next_sort_) {
            sort_by_cell();
            next_sort_ = events_ + 16 * p_.size();
        }
        const std::uint32_t i = heap_[0].id;
        now_ = heap_[0].t;
        ++events_;
        if (ev_axis_[i] >= 0) {
            cross(i);
            continue;
        }
        const auto j = std::uint32_t(ev_partner_[i]);
        if (count_[j] != ev_count_[i]) {
            predict(i, -1, 0);  // the partner collided since: stale
            continue;
        }
        collide(i, j);
        predict(i, -1, 0);
        predict(j, -1, 0);
    }
}

template <int D>
void MinimalEventDriven<D>::state(std::vector<double>& r, std::vector<double>& v) {
    const std::size_t n = p_.size();
    r.resize(n * D);
    v.resize(n * D);
    for (std::size_t i = 0; i < n; ++i) {
        const double dt = now_ - p_[i].t;
        for (int a = 0; a < D; ++a) {
            r[i * D + std::size_t(a)] = p_[i].r[a] + p_[i].v[a] * dt;
            v[i * D + std::size_t(a)] = p_[i].v[a];
        }
    }
}

template class MinimalEventDriven<2>;
template class MinimalEventDriven<3>;

}  // namespace gran::bench
