// Pair laws whose normal restitution depends on the impact speed (the normal relative velocity at
// contact): McNamara & Falcon 2005, Eq. (1), and the viscoelastic law of Brilliantov, Poeschel et
// al. Kernels in species/impact_restitution.hpp; the parameters shared with walls are declared in
// restitution_params.hpp.
#include "species/pair_law.hpp"
#include "species/restitution_params.hpp"

namespace gran {
namespace {

const ParamSpec kBeta =
    real("beta", "-1", "",
         "tangential restitution coefficient beta_ij (-1 = smooth, no rotation; "
         "1 = perfectly rough)",
         -1, 1);

const char* const kMcNamaraFalconDescription =
    R"md(
Normal restitution of the impact speed v = |g_n| (McNamara & Falcon 2005, Eq. 1):
r(v) = 1 - (1 - r0)(v/v0)^(1/5) for v <= v0 (viscoelastic), r0 (v/v0)^(-1/4) for v >= v0 (plastic).
Continuous at v0; r -> 1 as v -> 0. The paper: r0 = 0.95, v0 = 0.3 m/s (stainless steel).
Nominal restitution (for kinetic-theory estimates): r0.)md";

const char* const kViscoelasticDescription =
    R"md(
Viscoelastic spheres (Schwager & Poeschel 1998; Ramirez et al. 1999): e(v) = 1 - C1 x + C2 x^2,
x = gamma v^(1/5), C1 = 1.15345, C2 = (3/5) C1^2. Accurate to 4e-3 for x <= 0.3 (e >= 0.72);
beyond the series' minimum x = 0.7225 (e = 7/12) e is held constant so it never rises with speed.
Nominal restitution (for kinetic-theory estimates): 1.)md";

const bool mcnamara_falcon = PairLawRegistry::instance().add(PairLaw{
    "mcnamara_falcon",
    "hard-particle collision with r(v) = 1 - (1 - r0)(v/v0)^(1/5) below v0, r0 (v/v0)^(-1/4) above "
    "(McNamara & Falcon 2005, Eq. 1)",
    {mcnamara_falcon_r0_spec(), mcnamara_falcon_v0_spec(), kBeta},
    [](const Params& p, PairCoefficients& c) {
        c.restitution = mcnamara_falcon_impact_restitution(p.real("r0"), p.real("v0"));
        c.alpha = c.restitution.r0;  // nominal: r(v0)
        c.beta = p.real("beta");
    },
    kMcNamaraFalconDescription});

const bool viscoelastic = PairLawRegistry::instance().add(PairLaw{
    "viscoelastic",
    "hard-particle collision with the viscoelastic restitution e(v) = 1 - C1 x + C2 x^2, x = gamma "
    "v^(1/5) (Schwager & Poeschel 1998; valid for e >~ 0.8)",
    {viscoelastic_gamma_spec(), kBeta},
    [](const Params& p, PairCoefficients& c) {
        c.restitution = viscoelastic_impact_restitution(p.real("gamma"));
        c.alpha = 1.0;  // nominal: the v -> 0 limit
        c.beta = p.real("beta");
    },
    kViscoelasticDescription});

}  // namespace
}  // namespace gran
