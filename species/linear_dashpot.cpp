// The soft contact of Bhateja, Sharma & Singh, Phys. Fluids 28, 043301 (2016), Appendix: a linear
// spring-dashpot normal force with the dashpot set from the restitution (Eqs. A5, A6, A9 with A9's
// sign corrected) and a tangential dashpot capped by Coulomb friction, no tangential spring (Eqs.
// A7, A8; "k_t = 0"). Kernel: linear_dashpot_force (species/contact_laws.hpp). Frictionless, it
// also runs on the event-driven engine as its hard limit (instantaneous collisions with the same
// restitution), the limit k_n -> infinity of the DEM runs.
#include "libgran/engines/register_law.hpp"
#include "species/soft_contact.hpp"

namespace gran {
namespace {

struct LinearDashpot : soft_contact::LawBase<LinearDashpotContact> {
    static constexpr bool history = false;

    static Pair resolve(const Params& p, const ContactPartner& a, const ContactPartner& b,
                        const LawContext&) {
        const soft_contact::Request r = soft_contact::read(p, a, b);
        const soft_contact::LinearNormal n = soft_contact::linear_normal(r, p);
        Pair c;
        c.contact = {n.k_n, n.gamma_n, soft_contact::tangential_damping(r, n.gamma_n), r.mu};
        c.duration = n.duration;
        c.restitution = r.e;
        return c;
    }
    template <int D>
    [[gnu::always_inline]] static ContactForce<D> force(const Pair& c, double delta,
                                                        const Vec<D>& n, const Vec<D>& g,
                                                        double l_i, double l_j,
                                                        Vec<D>& /*spring*/) {
        return linear_dashpot_force<D>(c.contact, delta, n, g, l_i, l_j);
    }
    // Two contacts of spheres at once (the DEM engine's pair loop, two_contacts.hpp).
    static constexpr bool two_lanes = true;
    [[gnu::always_inline]] static void force_two(const Pair& a, const Pair& b,
                                                 two_contacts::Lane delta,
                                                 const two_contacts::Vec2<3>& n,
                                                 const two_contacts::Vec2<3>& g,
                                                 two_contacts::Lane l_i, two_contacts::Lane l_j,
                                                 ContactForce<3>& on_a, ContactForce<3>& on_b) {
        linear_dashpot_force_two(a.contact, b.contact, delta, n, g, l_i, l_j, on_a, on_b);
    }
    static double elastic_energy(const Pair& c, double delta, double /*spring2*/) {
        return 0.5 * c.contact.k_n * delta * delta;
    }
};

const char* const kDescription =
    R"md(
The paper's Eqs. (A5)-(A9): F_n = k_n delta - c_n g_n with c_n from e and the contact's reduced
mass (the grain's mass against a wall), tangential dashpot F_t = -min(c_t |g_t|, mu |F_n|) t, no
tangential spring (so c_t = 0 makes friction inactive; the paper gives no c_t). Give `stiffness`
or `contact_time`, not both; a contact time gives every contact (each with its own reduced mass)
that duration. Nominal restitution: e. Frictionless, it runs on the event-driven engine as its
hard limit (instantaneous collisions with restitution e).)md";

const bool registered = register_law<LinearDashpot>(
    "linear_dashpot",
    "soft contact: linear spring-dashpot with the dashpot from e, Coulomb-capped tangential "
    "dashpot, no tangential spring (Bhateja et al. 2016, Eqs. A5-A9)",
    soft_contact::common_schema(), kDescription);

}  // namespace
}  // namespace gran
