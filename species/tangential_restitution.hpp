#pragma once
// The tangential restitution beta of the hard-particle laws (constant_restitution, mcnamara_falcon,
// viscoelastic): one key, the same meaning in each. Grain-grain collisions take it (Barrat &
// Trizac 2002, Eq. (A12) for rough disks and spheres); a wall reflects the normal component only,
// so grain-wall contacts are smooth whatever beta says.
#include "libgran/core/params.hpp"
#include "libgran/plugins/law.hpp"

namespace gran::hard_sphere {

inline ParamSpec tangential_restitution_key() {
    return real("beta", "-1", "",
                "tangential restitution coefficient beta_ij of grain-grain collisions (-1 = "
                "smooth, no rotation; 1 = perfectly rough); wall collisions reflect the normal "
                "component only",
                -1, 1);
}

// beta of the contact of a grain with partner b (-1, smooth, against a wall).
inline double tangential_restitution(const Params& p, const ContactPartner& b) {
    return b.wall ? -1.0 : p.real("beta");
}

}  // namespace gran::hard_sphere
