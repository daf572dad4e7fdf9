#pragma once
// The force loop of the DEM engine templated on the contact law (libgran/plugins/law.hpp): pair
// contacts over the neighbour list, plane walls, and the elastic energy stored in the contacts.
// Included by libgran/engines/register_law.hpp, so each law's file instantiates the loops with its
// own law type (its kernel inlined, no call per contact); the engine reaches them through
// DemLawLoops, once per step.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "libgran/core/parallel.hpp"
#include "libgran/core/registry.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "libgran/engines/dem/two_contacts.hpp"

namespace gran {

template <int D>
template <class L>
void DemEngine<D>::accumulate_forces_with(double dt_advance) {
    if (p_.rotating()) {
        pair_forces<L, true>(dt_advance);
        stage_clock_.lap(stage_times_.pair_contacts);
        wall_forces<L, true>(dt_advance);
        stage_clock_.lap(stage_times_.wall_contacts);
    } else {
        pair_forces<L, false>(dt_advance);
        stage_clock_.lap(stage_times_.pair_contacts);
        wall_forces<L, false>(dt_advance);
        stage_clock_.lap(stage_times_.wall_contacts);
    }
}

// Pair contacts over the half neighbour list: force on i, its opposite on j (Newton's third law
// exactly, so the total momentum changes by round-off only).
//
// One thread sums each contact into f_ and tau_ as it goes, entry by entry. Several threads
// (DemSettings::threads) each take consecutive rows of the list (split_pair_rows) and add their
// contacts straight into the grains whose every entry lies in their rows, in the same entry
// order as one thread. The halo grains, partners of an earlier thread's rows, get their
// contacts in per-entry slots instead, summed after a barrier in the single thread's order
// (sum_halo_pair_forces). The same additions in the same order: the forces are the same bits
// for any thread count.
template <int D>
template <class L, bool Rot>
void DemEngine<D>::pair_forces(double dt_advance) {
    PairTally total{0, 0, counters_.max_overlap};
    if (threads_ <= 1) {
        pair_range<L, Rot, false>(dt_advance, 0, list_.entries(), total);
    } else {
        if (pair_split_stale_) split_pair_rows();
        const std::size_t entries = list_.entries();
        pair_force_.resize(entries);
        if constexpr (Rot) {
            pair_torque_i_.resize(entries);
            pair_torque_j_.resize(entries);
        }
        tallies_.assign(std::size_t(threads_), total);
        parallel_parts(threads_, [this, dt_advance](std::size_t part, std::size_t parts) {
            if (parts != std::size_t(threads_)) {  // granted fewer threads than split for
                if (part == 0)
                    pair_range<L, Rot, false>(dt_advance, 0, list_.entries(), tallies_[0]);
                return;
            }
            const std::uint32_t* start = list_.start.data();
            pair_range<L, Rot, true>(dt_advance, start[pair_rows_[part]],
                                     start[pair_rows_[part + 1]], tallies_[part]);
            parts_barrier();
            sum_halo_pair_forces(part, parts);
        });
        for (const PairTally& t : tallies_) total.add(t);
    }
    counters_.contacts += total.formed;
    counters_.active_contacts = total.active;
    counters_.active_contact_steps += total.active;
    counters_.max_overlap = total.worst;
}

// The contacts of entries [k0, k1): summed into f_, tau_ (Halo false); with Halo, summed into
// the grains that are not halo grains and stored in the entry's slots if one of its grains is
// (its forces are then summed by sum_halo_pair_forces); the tallies added to `tally`. Raw
// pointers in locals throughout (the byte stores to the contact flags may alias anything, which
// would reload every vector's data pointer per entry). Each entry's contact flag is written (a
// byte); its force slot only if it touches.
template <int D>
template <class L, bool Rot, bool Halo>
void DemEngine<D>::pair_range(double dt_advance, std::size_t k0, std::size_t k1, PairTally& tally) {
    constexpr bool kHistory = L::history;
    const std::size_t ns = mass_.size();
    const typename L::Pair* params = contacts_.template contacts<L>();
    // Pair parameters per contact class (ContactTable): one lookup of each partner's class.
    const std::uint32_t* class_of = contacts_.class_of.data();
    const std::size_t classes = contacts_.classes;
    const double* sigma = sigma_.data();
    const AngVec<D> zero = ang_zero<D>();
    std::uint64_t formed = 0, active = 0;
    double worst = tally.worst;
    // Minimum image per component without branches on the axis kind: a bounded axis has period
    // 0 and half-period infinity. Scalars, not a vector patched in memory (store forwarding).
    std::array<double, D> period{}, half{};
    for (std::size_t k = 0; k < std::size_t(D); ++k) {
        const bool per = box_.periodic[k];
        period[k] = per ? box_.length[int(k)] : 0.0;
        half[k] = per ? 0.5 * box_.length[int(k)] : kInf;
    }
    const std::uint32_t* owner = list_.owner.data();
    const std::uint32_t* partner = list_.partner.data();
    std::uint8_t* touching = list_.touching.data();
    Vec<D>* spring = list_.spring.data();
    const std::uint8_t* halo = halo_.data();
    const Vec<D>* r = p_.r.data();
    const Vec<D>* v = p_.v.data();
    const Vec<D>* v_pred = v_pred_.data();
    const AngVec<D>* w = p_.w.data();
    const AngVec<D>* w_pred = w_pred_.data();
    const std::uint32_t* species = p_.species.data();
    const double* radius = radius_.data();
    Vec<D>* f = f_.data();
    AngVec<D>* tau = tau_.data();
    Vec<D>* slot_force = pair_force_.data();
    AngVec<D>* slot_torque_i = pair_torque_i_.data();
    AngVec<D>* slot_torque_j = pair_torque_j_.data();
    // Blocks of entries in three passes, so that the square roots and divisions of different
    // contacts overlap instead of each heading one contact's chain of dependent operations:
    //  1. every entry's separation, and whether it touches (no branch), its flag updated;
    //  2. the distances and their inverses of the touching ones (independent iterations);
    //  3. their contacts, in increasing entry order as one loop over the entries would.
    // The operations and their order per contact are those of one loop: the same bits.
    constexpr std::size_t kBlock = 64;
    constexpr std::uint32_t kFormed = 0x80000000u;
    std::array<std::uint32_t, kBlock> hit;
    std::array<std::array<double, D>, kBlock> sep;
    std::array<double, kBlock> dist_of, inv_dist;
    // Laws that evaluate two sphere contacts per instruction say so (two_lanes, force_two).
    constexpr bool kTwoLanes = [] {
        if constexpr (D == 3 && requires { L::two_lanes; }) return L::two_lanes;
        return false;
    }();
    // A contact's force and torques added to its grains (halo grains: into the entry's slots).
    auto add_contact = [&](std::size_t k, std::uint32_t i, std::uint32_t j,
                           const ContactForce<D>& c) __attribute__((always_inline)) {
        if constexpr (Halo) {
            const bool halo_i = halo[i] != 0, halo_j = halo[j] != 0;
            if (!halo_i) {
                f[i] += c.force;
                if constexpr (Rot) tau[i] += c.torque_i;
            }
            if (!halo_j) {
                f[j] -= c.force;
                if constexpr (Rot) tau[j] += c.torque_j;
            }
            if (halo_i || halo_j) {
                slot_force[k] = c.force;
                if constexpr (Rot) {
                    slot_torque_i[k] = c.torque_i;
                    slot_torque_j[k] = c.torque_j;
                }
            }
        } else {
            f[i] += c.force;
            f[j] -= c.force;
            if constexpr (Rot) {
                tau[i] += c.torque_i;
                tau[j] += c.torque_j;
            }
        }
    };
    for (std::size_t b0 = k0; b0 < k1; b0 += kBlock) {
        const std::size_t b1 = std::min(k1, b0 + kBlock);
        std::size_t m = 0;
        for (std::size_t k = b0; k < b1; ++k) {
            const std::uint32_t i = owner[k], j = partner[k];
            const double sigma_ij = sigma[species[i] * ns + species[j]];
            double dist2 = 0;
            for (std::size_t a = 0; a < std::size_t(D); ++a) {
                double x = r[i][int(a)] - r[j][int(a)];
                x = x > half[a] ? x - period[a] : (x < -half[a] ? x + period[a] : x);
                sep[m][a] = x;
                dist2 += x * x;
            }
            const bool in = dist2 < sigma_ij * sigma_ij;  // false for NaN
            const std::uint8_t was = touching[k];
            touching[k] = std::uint8_t(in);
            dist_of[m] = dist2;
            hit[m] = std::uint32_t(k - b0) | (was ? 0u : kFormed);
            m += in ? 1 : 0;
        }
        for (std::size_t q = 0; q < m; ++q) {
            dist_of[q] = std::sqrt(dist_of[q]);
            inv_dist[q] = 1.0 / dist_of[q];
        }
        std::size_t q = 0;
        if constexpr (kTwoLanes) {
            // Two contacts at a time (two_contacts.hpp), each lane the operations of the loop
            // below; the contacts' forces are then added in entry order, as that loop adds them.
            using namespace two_contacts;
            for (; q + 2 <= m; q += 2) {
                const std::size_t ka = b0 + (hit[q] & ~kFormed), kb = b0 + (hit[q + 1] & ~kFormed);
                const bool forms_a = (hit[q] & kFormed) != 0, forms_b = (hit[q + 1] & kFormed) != 0;
                const std::uint32_t ia = owner[ka], ja = partner[ka];
                const std::uint32_t ib = owner[kb], jb = partner[kb];
                const std::uint32_t sia = species[ia], sja = species[ja];
                const std::uint32_t sib = species[ib], sjb = species[jb];
                const typename L::Pair& pa = params[class_of[sia] * classes + class_of[sja]];
                const typename L::Pair& pb = params[class_of[sib] * classes + class_of[sjb]];
                const Lane sigma_ij = lanes(sigma[sia * ns + sja], sigma[sib * ns + sjb]);
                Vec2<3> d;
                for (int a = 0; a < 3; ++a)
                    d.c[a] = lanes(sep[q][std::size_t(a)], sep[q + 1][std::size_t(a)]);
                const Vec2<3> nrm = scale(lanes(inv_dist[q], inv_dist[q + 1]), d);
                const Lane delta = sub(sigma_ij, lanes(dist_of[q], dist_of[q + 1]));  // (A6)
                active += 2;
                formed += std::uint64_t(forms_a) + std::uint64_t(forms_b);
                const Lane relative = _mm_div_pd(delta, sigma_ij);
                const double rel_a = first(relative), rel_b = second(relative);
                worst = rel_a > worst ? rel_a : worst;
                worst = rel_b > worst ? rel_b : worst;
                const Lane li = lanes(radius[sia], radius[sib]),
                           lj = lanes(radius[sja], radius[sjb]);
                Vec2<3> wpi{}, wpj{};
                if constexpr (Rot) {
                    wpi = lanes<3>(w_pred[ia], w_pred[ib]);
                    wpj = lanes<3>(w_pred[ja], w_pred[jb]);
                } else {
                    wpi = lanes<3>(zero, zero);
                    wpj = wpi;
                }
                const Vec2<3> g =
                    contact_velocity(lanes<3>(v_pred[ia], v_pred[ib]),
                                     lanes<3>(v_pred[ja], v_pred[jb]), wpi, wpj, li, lj, nrm);
                ContactForce<D> ca, cb;
                L::force_two(pa, pb, delta, nrm, g, li, lj, ca, cb);
                add_contact(ka, ia, ja, ca);
                add_contact(kb, ib, jb, cb);
            }
        }
        for (; q < m; ++q) {
            const std::size_t k = b0 + (hit[q] & ~kFormed);
            const bool forms = (hit[q] & kFormed) != 0;
            const std::uint32_t i = owner[k], j = partner[k];
            const std::uint32_t si = species[i], sj = species[j];
            const typename L::Pair& P = params[class_of[si] * classes + class_of[sj]];
            const double sigma_ij = sigma[si * ns + sj];
            Vec<D> d;
            for (std::size_t a = 0; a < std::size_t(D); ++a) d[int(a)] = sep[q][a];
            const double dist = dist_of[q];
            const Vec<D> nrm = inv_dist[q] * d;    // from j to i
            const double delta = sigma_ij - dist;  // (A6)
            ++active;
            if (forms) ++formed;
            // The largest relative overlap: a maximum, the same whatever order entries come in.
            const double relative = delta / sigma_ij;
            worst = relative > worst ? relative : worst;
            const double li = radius[si], lj = radius[sj];
            AngVec<D> wpi = zero, wpj = zero, whi = zero, whj = zero;
            if constexpr (Rot) {
                wpi = w_pred[i];
                wpj = w_pred[j];
                whi = w[i];
                whj = w[j];
            }
            // (A3) at the predicted velocities: the dampers' relative velocity.
            const Vec<D> g = contact_velocity<D>(v_pred[i], v_pred[j], wpi, wpj, li, lj, nrm);
            const ContactForce<D> c = [&] {
                if constexpr (kHistory) {
                    Vec<D>& xi = spring[k];
                    if (forms) xi.setZero();
                    // The spring integrates the half-step velocities that moved the positions; a
                    // new contact only over its in-contact part delta / closing speed.
                    const Vec<D> gh = contact_velocity<D>(v[i], v[j], whi, whj, li, lj, nrm);
                    const double closing = -gh.dot(nrm);
                    double dt_in = dt_advance;
                    if (forms && closing * dt_in > delta) dt_in = delta / closing;
                    advance_tangential_spring<D>(xi, nrm, Vec<D>(dt_in * gh));
                    return L::template force<D>(P, delta, nrm, g, li, lj, xi);
                } else {
                    (void)whi;
                    (void)whj;
                    (void)spring;
                    (void)v;
                    Vec<D> unused;
                    return L::template force<D>(P, delta, nrm, g, li, lj, unused);
                }
            }();
            add_contact(k, i, j, c);
        }
    }
    (void)halo;
    (void)slot_force;
    (void)slot_torque_i;
    (void)slot_torque_j;
    tally.formed += formed;
    tally.active += active;
    tally.worst = worst;
}

// Plane walls: the particle against an infinite mass (m_eff = m_i, lever arm 0 on the wall side)
// moving along its normal with velocity u(t): v_j = u n_axis in the relative velocity (A3).
// Wall by wall, so each particle's wall forces are added in wall order; several threads split a
// wall's candidates (wall_candidates_, in increasing index) into consecutive shares, which
// changes no bit of any particle's force. The normal forces that make the wall's impulse are
// summed afterwards in candidate order (one thread: as they come). The candidates are cut at
// the pair loop's rows once it has them (each thread then writes its own grains' forces), and
// in equal shares before.
template <int D>
template <class L, bool Rot>
void DemEngine<D>::wall_forces(double dt_advance) {
    double worst = counters_.max_overlap;
    if (wall_candidates_stale_) find_wall_candidates();
    // On several threads, once the pair stage has its rows: each thread takes the candidates in
    // its rows, whatever their number, so that it writes the forces of its own grains only (a
    // wall pass on one thread wrote the other thread's lines, which its drift then fetched back
    // across the cores: docs/performance.md, "The drift on the pair stage's rows").
    const bool on_rows = rows_split();
    for (std::size_t c = 0; c < 2 * D; ++c) {
        if (!walls_[c].present) continue;
        double impulse = 0;
        std::uint64_t formed = 0;
        const std::size_t m = wall_candidates_[c].size();
        // At least a quarter of min_particles_per_thread candidates per thread: a wall with
        // fewer (the side walls of a box, the floor of a small bed) is not worth a parallel
        // region of its own. A quarter, since a wall contact costs several times a grain's
        // drift: the floor of the settled bed of 10^4 grains (about 2500 contacts) gains
        // 2.3x from a second thread (docs/performance.md, "The wall pass split").
        const std::size_t per = std::max<std::size_t>(settings_.min_particles_per_thread / 4, 1);
        const int wall_threads = on_rows && m > 0  // a wall no grain can reach: no region
                                     ? threads_
                                     : int(std::min<std::size_t>(std::size_t(threads_), m / per));
        if (wall_threads <= 1) {
            wall_range<L, Rot>(dt_advance, c, 0, m, impulse, formed, worst, nullptr);
        } else {
            wall_touched_.resize(std::size_t(wall_threads));
            for (std::vector<double>& part : wall_touched_) part.clear();  // parts given no thread
            std::array<double, kMaxThreads> worst_of{};
            std::array<std::uint64_t, kMaxThreads> formed_of{};
            const auto share = [&, this](std::size_t part, std::size_t k0, std::size_t k1) {
                double unused = 0;
                worst_of[part] = worst;
                wall_range<L, Rot>(dt_advance, c, k0, k1, unused, formed_of[part], worst_of[part],
                                   &wall_touched_[part]);
            };
            if (on_rows) {  // the candidates are in increasing index: cut at the rows' bounds
                const std::uint32_t* cand = wall_candidates_[c].data();
                wall_shares_.resize(pair_rows_.size());
                for (std::size_t t = 0; t < pair_rows_.size(); ++t)
                    wall_shares_[t] = std::size_t(
                        std::lower_bound(cand, cand + m, std::uint32_t(pair_rows_[t])) - cand);
                parallel_ranges(threads_, wall_shares_, share);
            } else {
                parallel_chunks(wall_threads, m, share);
            }
            for (std::size_t part = 0; part < wall_touched_.size(); ++part) {
                worst = worst_of[part] > worst ? worst_of[part] : worst;
                formed += formed_of[part];
                for (const double f_n : wall_touched_[part]) impulse += f_n;  // candidate order
            }
        }
        wall_impulse_[c] += impulse * dt_advance;
        wall_hits_[c] += formed;
        counters_.wall_contacts += formed;
    }
    counters_.max_overlap = worst;
}

// The contacts with wall c of its candidates [k0, k1) (wall_candidates_[c]): forces and torques
// added to f_, tau_; normal forces summed into `impulse` (touched null) or appended to `touched`;
// contacts formed and the largest relative overlap into `formed` and `worst`.
template <int D>
template <class L, bool Rot>
void DemEngine<D>::wall_range(double dt_advance, std::size_t c, std::size_t k0, std::size_t k1,
                              double& impulse, std::uint64_t& formed, double& worst,
                              std::vector<double>* touched) {
    constexpr bool kHistory = L::history;
    constexpr std::size_t kWalls = 2 * D;
    const AngVec<D> zero = ang_zero<D>();
    const double t = now();
    double most = worst;
    std::vector<double> mine;  // on this thread's stack while it grows (see pair_range)
    if (touched) mine.swap(*touched);
    const Wall& w = walls_[c];
    const typename L::Pair* params =
        contacts_.template contacts<L>() + contacts_.wall_index(w.partner, 0);  // per species
    const int a = int(c / 2);
    const double inward = c % 2 == 0 ? 1.0 : -1.0;
    const double surface = w.base + w.motion.position(t);
    Vec<D> nrm = Vec<D>::Zero();
    nrm[a] = inward;  // into the gas
    Vec<D> vw = Vec<D>::Zero();
    vw[a] = w.motion.velocity(t);
    if (w.slide_axis >= 0) vw[w.slide_axis] = w.slide.velocity(t);
    double sum = 0;
    std::uint64_t count = 0;
    // Raw pointers (the byte stores to the contact flags may alias anything); a flag is
    // written only when it changes.
    const std::uint32_t* species = p_.species.data();
    const double* radius = radius_.data();
    const Vec<D>* r = p_.r.data();
    std::uint8_t* touching_of = wall_touching_.data() + c;
    const std::uint32_t* first = wall_candidates_[c].data() + k0;
    const std::uint32_t* last = wall_candidates_[c].data() + k1;
    for (auto it = first; it != last; ++it) {
        const std::size_t i = *it;
        const std::uint32_t s = species[i];
        const double R = radius[s];
        const double gap = inward * (r[i][a] - surface) - R;
        std::uint8_t& touching = touching_of[i * kWalls];
        if (!(gap < 0)) {
            if (touching) touching = 0;
            continue;
        }
        const double delta = -gap;
        const bool forms = touching == 0;
        touching = 1;
        if (forms) ++count;
        const typename L::Pair& P = params[s];
        const double relative = 0.5 * delta / R;
        most = relative > most ? relative : most;
        AngVec<D> wpi = zero, whi = zero;
        if constexpr (Rot) {
            wpi = w_pred_[i];
            whi = p_.w[i];
        }
        const Vec<D> g = contact_velocity<D>(v_pred_[i], vw, wpi, zero, R, 0.0, nrm);
        const ContactForce<D> cf = [&] {
            if constexpr (kHistory) {
                Vec<D>& xi = wall_spring_[i * kWalls + c];
                if (forms) xi.setZero();
                const Vec<D> gh = contact_velocity<D>(p_.v[i], vw, whi, zero, R, 0.0, nrm);
                const double closing = -gh.dot(nrm);
                double dt_in = dt_advance;
                if (forms && closing * dt_in > delta) dt_in = delta / closing;
                advance_tangential_spring<D>(xi, nrm, Vec<D>(dt_in * gh));
                return L::template force<D>(P, delta, nrm, g, R, 0.0, xi);
            } else {
                (void)whi;
                Vec<D> unused;
                return L::template force<D>(P, delta, nrm, g, R, 0.0, unused);
            }
        }();
        f_[i] += cf.force;
        if constexpr (Rot) tau_[i] += cf.torque_i;
        if (touched) {
            mine.push_back(cf.f_n);
        } else {
            sum += cf.f_n;
        }
    }
    impulse += sum;
    formed += count;
    if (touched) touched->swap(mine);
    worst = most;
}

// Elastic energy in the contacts: normal and tangential springs of the current pair and wall
// contacts (L::elastic_energy).
template <int D>
template <class L>
double DemEngine<D>::elastic_energy_with() const {
    const std::size_t n = p_.size(), ns = mass_.size();
    const typename L::Pair* params = contacts_.template contacts<L>();
    double e = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t s = p_.species[i];
        for (std::uint32_t k = list_.start[i]; k < list_.start[i + 1]; ++k) {
            const std::uint32_t j = list_.partner[k];
            const std::size_t pij = s * ns + p_.species[j];
            const double dist = box_.separation(p_.r[i], p_.r[j]).norm();
            if (!(dist < sigma_[pij])) continue;
            const double xi2 = history_ ? list_.spring[k].squaredNorm() : 0.0;
            const std::size_t cij = contacts_.pair_index(s, p_.species[j]);
            e += L::elastic_energy(params[cij], sigma_[pij] - dist, xi2);
        }
    }
    const double t = now();
    for (std::size_t c = 0; c < 2 * D; ++c) {
        if (!walls_[c].present) continue;
        const int a = int(c / 2);
        const double inward = c % 2 == 0 ? 1.0 : -1.0;
        const double surface = wall_position(int(c), t);
        const typename L::Pair* wp = params + contacts_.wall_index(walls_[c].partner, 0);
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t s = p_.species[i];
            const double gap = inward * (p_.r[i][a] - surface) - radius_[s];
            if (!(gap < 0)) continue;
            const double xi2 = history_ ? wall_spring_[i * 2 * D + c].squaredNorm() : 0.0;
            e += L::elastic_energy(wp[s], -gap, xi2);
        }
    }
    return e;
}

// The pair virial of the contacts (DemEngine::contact_virial): each contact's force recomputed as
// the last evaluation made it (positions and predicted velocities unchanged since; the spring as
// that evaluation left it, on a copy), so nothing of the state changes.
template <int D>
template <class L>
std::vector<double> DemEngine<D>::contact_virial_with() const {
    const std::size_t n = p_.size(), ns = mass_.size();
    const typename L::Pair* params = contacts_.template contacts<L>();
    const AngVec<D> zero = ang_zero<D>();
    std::vector<double> virial(ns * D, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t si = p_.species[i];
        for (std::uint32_t k = list_.start[i]; k < list_.start[i + 1]; ++k) {
            const std::uint32_t j = list_.partner[k];
            const std::uint32_t sj = p_.species[j];
            const double sigma_ij = sigma_[si * ns + sj];
            const Vec<D> d = box_.separation(p_.r[i], p_.r[j]);  // from j to i
            const double dist = d.norm();
            if (!(dist < sigma_ij)) continue;
            const Vec<D> nrm = (1.0 / dist) * d;
            const double li = radius_[si], lj = radius_[sj];
            const AngVec<D> wi = p_.rotating() ? w_pred_[i] : zero;
            const AngVec<D> wj = p_.rotating() ? w_pred_[j] : zero;
            const Vec<D> g = contact_velocity<D>(v_pred_[i], v_pred_[j], wi, wj, li, lj, nrm);
            Vec<D> xi = Vec<D>::Zero();
            if constexpr (L::history) xi = list_.spring[k];
            const ContactForce<D> c = L::template force<D>(params[contacts_.pair_index(si, sj)],
                                                           sigma_ij - dist, nrm, g, li, lj, xi);
            for (int a = 0; a < D; ++a) {
                const double w = 0.5 * d[a] * c.force[a];
                virial[si * D + std::size_t(a)] += w;
                virial[sj * D + std::size_t(a)] += w;
            }
        }
    }
    return virial;
}

// Registers the loops of law L for disks and spheres (called by register_law<L>).
template <class L>
void register_dem_loops(const std::string& name) {
    Registry<DemLawLoops<2>>::instance().add({name,
                                              &DemEngine<2>::template accumulate_forces_with<L>,
                                              &DemEngine<2>::template elastic_energy_with<L>,
                                              &DemEngine<2>::template contact_virial_with<L>});
    Registry<DemLawLoops<3>>::instance().add({name,
                                              &DemEngine<3>::template accumulate_forces_with<L>,
                                              &DemEngine<3>::template elastic_energy_with<L>,
                                              &DemEngine<3>::template contact_virial_with<L>});
}

}  // namespace gran
