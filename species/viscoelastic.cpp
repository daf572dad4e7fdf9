// Restitution of viscoelastic spheres as a function of the impact speed v, to order v^(2/5):
// e(v) = 1 - C1 x + C2 x^2, x = gamma v^(1/5) (Schwager & Poeschel, Phys. Rev. E 57, 650 (1998);
// Ramirez et al., Phys. Rev. E 60, 4465 (1999)); valid for e >~ 0.8. Kernel and range of validity:
// species/impact_restitution.hpp.
#include "libgran/engines/register_law.hpp"
#include "species/impact_restitution.hpp"
#include "species/tangential_restitution.hpp"

namespace gran {
namespace {

struct Viscoelastic {
    struct Pair {
        double gamma = 0;  // A kappa^(2/5), (time/length)^(1/5)
        double beta = -1;  // tangential restitution of grain-grain collisions
    };
    static constexpr bool impact_dependent = true;

    static Pair resolve(const Params& p, const ContactPartner&, const ContactPartner& b,
                        const LawContext&) {
        return {p.real("gamma"), hard_sphere::tangential_restitution(p, b)};
    }
    static double normal_restitution(const Pair& c, double impact_speed) {
        return viscoelastic_restitution(std::fabs(impact_speed), c.gamma);
    }
    static double tangential_restitution(const Pair& c) { return c.beta; }
    static double nominal_restitution(const Pair&) { return 1.0; }  // the v -> 0 limit
    static bool rotates(const Pair& c) { return c.beta != -1.0; }
    // The same contact for every pair of species: they may share a contact class.
    static PartnerProperties partner_properties(const Params&) { return kNoPartnerProperties; }
};

const char* const kDescription =
    R"md(
Viscoelastic spheres (Schwager & Poeschel 1998; Ramirez et al. 1999): e(v) = 1 - C1 x + C2 x^2,
x = gamma v^(1/5), C1 = 1.15345, C2 = (3/5) C1^2. Accurate to 4e-3 for x <= 0.3 (e >= 0.72);
beyond the series' minimum x = 0.7225 (e = 7/12) e is held constant so it never rises with speed.
Nominal restitution (for kinetic-theory estimates): 1.)md";

const bool registered = register_law<Viscoelastic>(
    "viscoelastic",
    "hard-particle collision with the viscoelastic restitution e(v) = 1 - C1 x + C2 x^2, x = gamma "
    "v^(1/5) (Schwager & Poeschel 1998; valid for e >~ 0.8)",
    {real("gamma", "", "(time/length)^(1/5)",
          "gamma = A kappa^(2/5) of the viscoelastic series e = 1 - C1 gamma v^(1/5) + C2 "
          "gamma^2 v^(2/5)",
          0, 1e308),
     hard_sphere::tangential_restitution_key()},
    kDescription);

}  // namespace
}  // namespace gran
