#pragma once
// The force loop of the DEM engine templated on the contact law (libgran/plugins/law.hpp): pair
// contacts over the neighbour list, plane walls, and the elastic energy stored in the contacts.
// Included by libgran/engines/register_law.hpp, so each law's file instantiates the loops with its
// own law type (its kernel inlined, no call per contact); the engine reaches them through
// DemLawLoops, once per step.
#include <algorithm>
#include <array>
#include <cmath>

#include "libgran/core/registry.hpp"
#include "libgran/engines/dem/engine.hpp"

namespace gran {

template <int D>
template <class L>
void DemEngine<D>::accumulate_forces_with(double dt_advance) {
    if (p_.rotating()) {
        pair_forces<L, true>(dt_advance);
        wall_forces<L, true>(dt_advance);
    } else {
        pair_forces<L, false>(dt_advance);
        wall_forces<L, false>(dt_advance);
    }
}

// Pair contacts over the half neighbour list: force on i, its opposite on j (Newton's third law
// exactly, so the total momentum changes by round-off only). Raw pointers throughout (the byte
// stores to the contact flags may alias anything, which would reload every vector's data pointer
// per entry); nothing is written for an entry that neither touches nor touched.
template <int D>
template <class L, bool Rot>
void DemEngine<D>::pair_forces(double dt_advance) {
    constexpr bool kHistory = L::history;
    const std::size_t ns = mass_.size();
    const typename L::Pair* params = contacts_.template contacts<L>();
    // Pair parameters per contact class (ContactTable): one lookup of each partner's class.
    const std::uint32_t* class_of = contacts_.class_of.data();
    const std::size_t classes = contacts_.classes;
    const double* sigma = sigma_.data();
    const AngVec<D> zero = ang_zero<D>();
    std::uint64_t formed = 0, active = 0;
    double worst = counters_.max_overlap;
    // Minimum image per component without branches on the axis kind: a bounded axis has period
    // 0 and half-period infinity. Scalars, not a vector patched in memory (store forwarding).
    std::array<double, D> period{}, half{};
    for (std::size_t k = 0; k < std::size_t(D); ++k) {
        const bool per = box_.periodic[k];
        period[k] = per ? box_.length[int(k)] : 0.0;
        half[k] = per ? 0.5 * box_.length[int(k)] : kInf;
    }
    const std::size_t entries = list_.entries();
    const std::uint32_t* owner = list_.owner.data();
    const std::uint32_t* partner = list_.partner.data();
    std::uint8_t* touching = list_.touching.data();
    Vec<D>* spring = list_.spring.data();
    const Vec<D>* r = p_.r.data();
    const Vec<D>* v = p_.v.data();
    const Vec<D>* v_pred = v_pred_.data();
    const AngVec<D>* w = p_.w.data();
    const AngVec<D>* w_pred = w_pred_.data();
    const std::uint32_t* species = p_.species.data();
    const double* radius = radius_.data();
    Vec<D>* f = f_.data();
    AngVec<D>* tau = tau_.data();
    // One flat loop over the entries (no per-row branches: most rows of a dilute gas are empty).
    for (std::size_t k = 0; k < entries; ++k) {
        const std::uint32_t i = owner[k], j = partner[k];
        const std::uint32_t si = species[i], sj = species[j];
        const typename L::Pair& P = params[class_of[si] * classes + class_of[sj]];
        const double sigma_ij = sigma[si * ns + sj];
        std::array<double, D> dc;
        double dist2 = 0;
        for (std::size_t a = 0; a < std::size_t(D); ++a) {
            double x = r[i][int(a)] - r[j][int(a)];
            x = x > half[a] ? x - period[a] : (x < -half[a] ? x + period[a] : x);
            dc[a] = x;
            dist2 += x * x;
        }
        if (!(dist2 < sigma_ij * sigma_ij)) {
            if (touching[k]) touching[k] = 0;
            continue;
        }
        Vec<D> d;
        for (std::size_t a = 0; a < std::size_t(D); ++a) d[int(a)] = dc[a];
        const double dist = std::sqrt(dist2);
        const Vec<D> nrm = (1.0 / dist) * d;   // from j to i
        const double delta = sigma_ij - dist;  // (A6)
        const bool forms = touching[k] == 0;
        touching[k] = 1;
        ++active;
        if (forms) ++formed;
        if (delta > worst * sigma_ij) worst = delta / sigma_ij;
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
        f[i] += c.force;
        f[j] -= c.force;
        if constexpr (Rot) {
            tau[i] += c.torque_i;
            tau[j] += c.torque_j;
        }
    }
    counters_.contacts += formed;
    counters_.active_contacts = active;
    counters_.max_overlap = worst;
}

// Plane walls: the particle against an infinite mass (m_eff = m_i, lever arm 0 on the wall side)
// moving along its normal with velocity u(t): v_j = u n_axis in the relative velocity (A3).
template <int D>
template <class L, bool Rot>
void DemEngine<D>::wall_forces(double dt_advance) {
    constexpr bool kHistory = L::history;
    constexpr std::size_t kWalls = 2 * D;
    const std::size_t n = p_.size();
    const AngVec<D> zero = ang_zero<D>();
    const double t = now();
    double worst = counters_.max_overlap;
    for (std::size_t c = 0; c < kWalls; ++c) {
        const Wall& w = walls_[c];
        if (!w.present) continue;
        const typename L::Pair* params =
            contacts_.template contacts<L>() + contacts_.wall_index(w.partner, 0);  // per species
        const int a = int(c / 2);
        const double inward = c % 2 == 0 ? 1.0 : -1.0;
        const double surface = w.base + w.motion.position(t);
        Vec<D> nrm = Vec<D>::Zero();
        nrm[a] = inward;  // into the gas
        Vec<D> vw = Vec<D>::Zero();
        vw[a] = w.motion.velocity(t);
        double impulse = 0;
        std::uint64_t formed = 0;
        // Raw pointers (the byte stores to the contact flags may alias anything); a flag is
        // written only when it changes.
        const std::uint32_t* species = p_.species.data();
        const double* radius = radius_.data();
        const Vec<D>* r = p_.r.data();
        std::uint8_t* touching_of = wall_touching_.data() + c;
        for (std::size_t i = 0; i < n; ++i) {
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
            if (forms) ++formed;
            const typename L::Pair& P = params[s];
            if (delta > worst * 2 * R) worst = 0.5 * delta / R;
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
            impulse += cf.f_n;
        }
        wall_impulse_[c] += impulse * dt_advance;
        wall_hits_[c] += formed;
        counters_.wall_contacts += formed;
    }
    counters_.max_overlap = worst;
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

// Registers the loops of law L for disks and spheres (called by register_law<L>).
template <class L>
void register_dem_loops(const std::string& name) {
    Registry<DemLawLoops<2>>::instance().add({name,
                                              &DemEngine<2>::template accumulate_forces_with<L>,
                                              &DemEngine<2>::template elastic_energy_with<L>});
    Registry<DemLawLoops<3>>::instance().add({name,
                                              &DemEngine<3>::template accumulate_forces_with<L>,
                                              &DemEngine<3>::template elastic_energy_with<L>});
}

}  // namespace gran
