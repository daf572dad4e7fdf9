// Impact-speed dependent restitution of McNamara & Falcon 2005, Eq. (1): the viscoelastic regime
// 1 - (1 - r0)(v/v0)^(1/5) below the yield velocity v0 joined to the plastic regime
// r0 (v/v0)^(-1/4) above it, v the normal impact speed (relative to the wall for a wall contact:
// "in the same way as collisions between particles, except the wall has infinite mass"). Kernel:
// species/impact_restitution.hpp.
#include "libgran/engines/register_law.hpp"
#include "species/impact_restitution.hpp"
#include "species/tangential_restitution.hpp"

namespace gran {
namespace {

struct McNamaraFalcon {
    struct Pair {
        double r0 = kMcNamaraFalconR0;
        double v0 = 1;     // velocity unit of the scene
        double beta = -1;  // tangential restitution of grain-grain collisions
    };
    static constexpr bool impact_dependent = true;

    static Pair resolve(const Params& p, const ContactPartner&, const ContactPartner& b,
                        const LawContext&) {
        return {p.real("r0"), p.real("v0"), hard_sphere::tangential_restitution(p, b)};
    }
    static double normal_restitution(const Pair& c, double impact_speed) {
        return mcnamara_falcon_restitution(std::fabs(impact_speed), c.r0, c.v0);
    }
    static double tangential_restitution(const Pair& c) { return c.beta; }
    static double nominal_restitution(const Pair& c) { return c.r0; }  // r(v0)
    static bool rotates(const Pair& c) { return c.beta != -1.0; }
    // The same contact for every pair of species: they may share a contact class.
    static PartnerProperties partner_properties(const Params&) { return kNoPartnerProperties; }
};

const char* const kDescription =
    R"md(
Normal restitution of the impact speed v = |g_n| (McNamara & Falcon 2005, Eq. 1):
r(v) = 1 - (1 - r0)(v/v0)^(1/5) for v <= v0 (viscoelastic), r0 (v/v0)^(-1/4) for v >= v0 (plastic).
Continuous at v0; r -> 1 as v -> 0. The paper: r0 = 0.95, v0 = 0.3 m/s (stainless steel), for
grains and walls alike. Nominal restitution (for kinetic-theory estimates): r0.)md";

const bool registered = register_law<McNamaraFalcon>(
    "mcnamara_falcon",
    "hard-particle collision with r(v) = 1 - (1 - r0)(v/v0)^(1/5) below v0, r0 (v/v0)^(-1/4) above "
    "(McNamara & Falcon 2005, Eq. 1)",
    {real("r0", "0.95", "",
          "restitution r0 at the yield velocity v0 (McNamara & Falcon 2005: 0.95)", 0, 1, true,
          false),
     real("v0", "", "velocity",
          "yield velocity v0 (McNamara & Falcon 2005: 0.3 m/s for stainless steel)", 0, 1e308,
          true),
     hard_sphere::tangential_restitution_key()},
    kDescription);

}  // namespace
}  // namespace gran
