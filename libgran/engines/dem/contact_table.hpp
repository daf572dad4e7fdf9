#pragma once
// Per-contact parameters of the soft-sphere DEM engine (issue #5): one resolved parameter set per
// species pair and one per species against the walls, built from requested properties (stiffness
// or contact duration, restitution, friction, tangential damping) with the closed forms of
// species/contact_laws.hpp, and the force dispatch the engine's loops call with the law as a
// template parameter (no switch or virtual call per contact).
//
// Laws (species/contact_laws.hpp):
//   linear_dashpot  Bhateja, Sharma & Singh, Phys. Fluids 28, 043301 (2016), Eqs. (A5)-(A9):
//                   F_n = k_n delta - gamma_n g_n, F_t = -min(gamma_t |g_t|, mu |F_n|) t.
//   cundall_strack  the same normal force and a tangential spring with history, k_t = ratio k_n.
//   hertz_mindlin   F_n = k_n delta^{3/2} - gamma_n delta^{1/4} g_n (Tsuji damping), tangential
//                   spring k_t delta^{1/2} with history; its contact duration depends on the impact
//                   speed, so a reference speed defines t_c.
//
// Masses: the reduced mass m_eff = m_i m_j / (m_i + m_j) of Eq. (A9) for a pair, m_eff = m_i for a
// wall (infinite mass).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/vec.hpp"
#include "species/contact_laws.hpp"
#include "species/species.hpp"

namespace gran {

enum class DemLaw { linear_dashpot, cundall_strack, hertz_mindlin };

const char* dem_law_name(DemLaw law);

// Requested properties of one kind of contact (a species pair, or a species against the walls).
struct DemContactSpec {
    double k_n = 0;  // normal stiffness (hertz_mindlin: coefficient of delta^{3/2}); 0: from t_c
    double t_c = 0;  // contact duration to match when k_n = 0 (hertz_mindlin: at reference_speed)
    double e = 1;    // normal restitution, (0, 1] (hertz_mindlin: [0.01, 1])
    double mu = 0;   // Coulomb friction coefficient mu_p (Eq. A8), >= 0
    double gamma_t = 0;  // tangential damping c_t (Eq. A7; hertz_mindlin: coefficient of
                         // delta^{1/4}), >= 0
    // cundall_strack, hertz_mindlin: k_t = k_t_ratio k_n. 2/7 gives k_t / m_t = k_n / m_eff for
    // equal uniform spheres (tangential and normal oscillations of equal period).
    double k_t_ratio = 2.0 / 7.0;
    // >= 0: gamma_t = gamma_t_ratio x gamma_n of the same contact (replaces gamma_t); the paper
    // gives no c_t, and c_t = c_n is a natural reading of "a tangential dashpot" like the normal
    // one.
    double gamma_t_ratio = -1;
    double reference_speed = 0;  // hertz_mindlin: impact speed at which t_c is defined, > 0
};

// Resolved parameters of one contact kind, read directly by the engine.
struct DemContactParams {
    double k_n = 0, gamma_n = 0, k_t = 0, gamma_t = 0, mu = 0;
    double m_eff = 0;        // reduced mass (a wall: the particle mass)
    double sigma = 0;        // contact distance: R_i + R_j (a wall: R_i)
    double duration = 0;     // t_c of a head-on contact (hertz_mindlin: at reference_speed)
    double restitution = 1;  // requested e
};

// Resolves a spec for a contact of reduced mass m_eff and contact distance sigma; `what` names the
// contact in error messages. Throws std::invalid_argument for out-of-range requests.
DemContactParams resolve_dem_contact(DemLaw law, const DemContactSpec& spec, double m_eff,
                                     double sigma, const std::string& what);

class DemContactTable {
  public:
    // Every species pair gets `pair`. Walls: each species against a wall gets the spring of its
    // own pair (the same k_n as a grain-grain contact of that species) with the other properties
    // of `pair`; the second constructor takes the wall properties separately (e_w, mu_w, ...).
    DemContactTable(const SpeciesTable& species, DemLaw law, const DemContactSpec& pair);
    DemContactTable(const SpeciesTable& species, DemLaw law, const DemContactSpec& pair,
                    const DemContactSpec& wall);

    // Overrides one unordered species pair (both orders), or one species against the walls.
    void set_pair(std::size_t a, std::size_t b, const DemContactSpec& spec);
    void set_wall(std::size_t s, const DemContactSpec& spec);

    DemLaw law() const { return law_; }
    std::size_t species_count() const { return mass_.size(); }
    const DemContactParams& pair(std::size_t a, std::size_t b) const {
        return pairs_[a * mass_.size() + b];
    }
    const DemContactParams& wall(std::size_t s) const { return walls_[s]; }
    // The wall contact of species s with another restitution e (a wall driver's own e_w).
    DemContactParams wall_with_restitution(std::size_t s, double e) const;
    const std::vector<DemContactParams>& pairs() const { return pairs_; }  // ns x ns
    const std::vector<DemContactParams>& walls() const { return walls_; }  // ns

    // Shortest contact duration over the pairs, and also over the walls if `with_walls`.
    double shortest_duration(bool with_walls) const;
    // The law keeps a tangential spring per contact.
    bool needs_history() const { return law_ != DemLaw::linear_dashpot; }
    // Some contact has friction (mu > 0): angular velocities are needed.
    bool needs_rotation() const;

  private:
    DemLaw law_;
    std::vector<double> mass_, diameter_;
    std::vector<DemContactParams> pairs_, walls_;
    std::vector<DemContactSpec> wall_specs_;
};

// ---------------------------------------------------------------------------------------------
// Kernel dispatch. g: contact-point relative velocity (contact_velocity()) at the velocities the
// dampers see; xi: the contact's tangential spring, already advanced (unused by linear_dashpot).
template <DemLaw L, int D>
inline ContactForce<D> dem_contact_force(const DemContactParams& p, double delta, const Vec<D>& n,
                                         const Vec<D>& g, double l_i, double l_j, Vec<D>& xi) {
    if constexpr (L == DemLaw::linear_dashpot) {
        (void)xi;
        return linear_dashpot_force<D>(LinearDashpotContact{p.k_n, p.gamma_n, p.gamma_t, p.mu},
                                       delta, n, g, l_i, l_j);
    } else if constexpr (L == DemLaw::cundall_strack) {
        return cundall_strack_force<D>(
            CundallStrackContact{p.k_n, p.gamma_n, p.k_t, p.gamma_t, p.mu}, delta, n, g, l_i, l_j,
            xi);
    } else {
        return hertz_mindlin_force<D>(HertzMindlinContact{p.k_n, p.gamma_n, p.k_t, p.gamma_t, p.mu},
                                      delta, n, g, l_i, l_j, xi);
    }
}

// Elastic energy stored in one contact: normal spring (k_n delta^2 / 2, Hertz (2/5) k_n
// delta^{5/2}) plus the tangential spring (k_t |xi|^2 / 2, Hertz with k_t delta^{1/2}).
inline double dem_contact_energy(DemLaw law, const DemContactParams& p, double delta, double xi2) {
    switch (law) {
        case DemLaw::linear_dashpot:
            return 0.5 * p.k_n * delta * delta;
        case DemLaw::cundall_strack:
            return 0.5 * p.k_n * delta * delta + 0.5 * p.k_t * xi2;
        case DemLaw::hertz_mindlin:
        default: {
            const double root = std::sqrt(delta);
            return 0.4 * p.k_n * delta * delta * root + 0.5 * p.k_t * root * xi2;
        }
    }
}

}  // namespace gran
