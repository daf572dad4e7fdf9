// Constant normal restitution alpha and tangential restitution beta (Barrat & Trizac 2002, Eq. (1)
// and Appendix A). The default law of every pair.
#include "species/pair_law.hpp"

namespace gran {
namespace {

const char* const kDescription =
    R"md(
The default law of every pair: alpha and beta of Barrat & Trizac 2002, Eq. (1) and Appendix A.
Its nominal restitution is alpha.)md";

const bool registered = PairLawRegistry::instance().add(PairLaw{
    "constant_restitution",
    "hard-particle collision with constant normal (alpha) and tangential (beta) restitution",
    {real("alpha", "1", "", "normal restitution coefficient alpha_ij (1 = elastic)", 0, 1, true,
          false),
     real("beta", "-1", "",
          "tangential restitution coefficient beta_ij (-1 = smooth, no rotation; 1 = perfectly "
          "rough)",
          -1, 1)},
    [](const Params& p, PairCoefficients& c) {
        c.alpha = p.real("alpha");
        c.beta = p.real("beta");
        c.restitution = constant_impact_restitution(c.alpha);
    },
    kDescription});

}  // namespace
}  // namespace gran
