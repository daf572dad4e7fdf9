// Cundall & Strack, Geotechnique 29, 47 (1979): the linear normal spring-dashpot of linear_dashpot
// and a tangential spring with history, k_t = tangential_stiffness_ratio k_n, plus the tangential
// dashpot, capped by Coulomb friction (the spring rescaled to the cap on slip). Kernel:
// cundall_strack_force (species/contact_laws.hpp).
#include "libgran/engines/register_law.hpp"
#include "species/soft_contact.hpp"

namespace gran {
namespace {

struct CundallStrack : soft_contact::LawBase<CundallStrackContact> {
    static constexpr bool history = true;

    static Pair resolve(const Params& p, const ContactPartner& a, const ContactPartner& b,
                        const LawContext&) {
        const soft_contact::Request r = soft_contact::read(p, a, b);
        const soft_contact::LinearNormal n = soft_contact::linear_normal(r, p);
        Pair c;
        c.contact = {n.k_n, n.gamma_n, p.real("tangential_stiffness_ratio") * n.k_n,
                     soft_contact::tangential_damping(r, n.gamma_n), r.mu};
        c.duration = n.duration;
        c.restitution = r.e;
        return c;
    }
    template <int D>
    static ContactForce<D> force(const Pair& c, double delta, const Vec<D>& n, const Vec<D>& g,
                                 double l_i, double l_j, Vec<D>& spring) {
        return cundall_strack_force<D>(c.contact, delta, n, g, l_i, l_j, spring);
    }
    static double elastic_energy(const Pair& c, double delta, double spring2) {
        return 0.5 * c.contact.k_n * delta * delta + 0.5 * c.contact.k_t * spring2;
    }
};

const char* const kDescription =
    R"md(
The normal force of `linear_dashpot` and a tangential spring k_t = `tangential_stiffness_ratio`
k_n with history (one spring per contact, kept across neighbour-list rebuilds) plus the tangential
dashpot, capped by Coulomb friction; on slip the spring is rescaled to what the cap allows (Luding
2008). With c_t = 0, a large mu and k_t / m_t = k_n / m_eff (2/7 for equal spheres) a collision
ends with the perfectly rough g_t' = -g_t. Frictionless, it runs on the event-driven engine as its
hard limit.)md";

const bool registered = register_law<CundallStrack>(
    "cundall_strack",
    "soft contact: linear spring-dashpot normal force and a tangential spring with history, "
    "capped by Coulomb friction (Cundall & Strack 1979)",
    [] {
        Schema s = soft_contact::common_schema();
        s.push_back(soft_contact::tangential_stiffness_ratio_spec());
        return s;
    }(),
    kDescription);

}  // namespace
}  // namespace gran
