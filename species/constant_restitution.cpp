// Constant normal restitution alpha and tangential restitution beta: Barrat & Trizac 2002, Eq. (1)
// (g_n' = -alpha g_n) and Appendix A (g_t' = -beta g_t of the contact points). The default law of
// every contact. Against a wall only the normal component is reflected (the walls of the paper,
// Sec. III A), so beta applies to grain-grain collisions.
#include "libgran/engines/register_law.hpp"
#include "species/tangential_restitution.hpp"

namespace gran {
namespace {

struct ConstantRestitution {
    struct Pair {
        double alpha = 1;  // normal restitution, (0, 1]
        double beta = -1;  // tangential restitution, [-1, 1]; -1 smooth
    };
    static constexpr bool impact_dependent = false;

    static Pair resolve(const Params& p, const ContactPartner&, const ContactPartner& b,
                        const LawContext&) {
        return {p.real("alpha"), hard_sphere::tangential_restitution(p, b)};
    }
    static double normal_restitution(const Pair& c, double /*impact_speed*/) { return c.alpha; }
    static double tangential_restitution(const Pair& c) { return c.beta; }
    static double nominal_restitution(const Pair& c) { return c.alpha; }
    static bool rotates(const Pair& c) { return c.beta != -1.0; }
    // The same contact for every pair of species: they may share a contact class.
    static PartnerProperties partner_properties(const Params&) { return kNoPartnerProperties; }
};

const char* const kDescription =
    R"md(
The default law of every contact: alpha and beta of Barrat & Trizac 2002, Eq. (1) and Appendix A
(rough collisions for unequal inertia factors). Against a wall only the normal component is
reflected, so beta applies to grain-grain collisions. Its nominal restitution is alpha.
Event-driven engine only (the dem engine needs a soft-contact law).)md";

const bool registered = register_law<ConstantRestitution>(
    "constant_restitution",
    "hard-particle collision with constant normal (alpha) and tangential (beta) restitution",
    {real("alpha", "1", "", "normal restitution coefficient alpha_ij (1 = elastic)", 0, 1, true,
          false),
     hard_sphere::tangential_restitution_key()},
    kDescription);

}  // namespace
}  // namespace gran
