#pragma once
// Scene parameters of the impact-speed dependent restitution laws, declared once and shared by
// the pair laws (species/impact_restitution_laws.cpp) and the walls (drivers/wall_driver.hpp).
#include "libgran/core/params.hpp"
#include "species/impact_restitution.hpp"

namespace gran {

inline ParamSpec mcnamara_falcon_r0_spec(std::string def = "0.95") {
    return real("r0", std::move(def), "",
                "restitution r0 at the yield velocity v0 (McNamara & Falcon 2005: 0.95)", 0, 1,
                true, false);
}
inline ParamSpec mcnamara_falcon_v0_spec(std::string def = "") {
    return real("v0", std::move(def), "velocity",
                "yield velocity v0 (McNamara & Falcon 2005: 0.3 m/s for stainless steel)", 0, 1e308,
                true);
}
inline ParamSpec viscoelastic_gamma_spec() {
    return real("gamma", "", "(time/length)^(1/5)",
                "gamma = A kappa^(2/5) of the viscoelastic series e = 1 - C1 gamma v^(1/5) + C2 "
                "gamma^2 v^(2/5)",
                0, 1e308);
}

// Wall restitution: `restitution` (constant) or `restitution_law` with its parameters.
inline Schema wall_restitution_schema() {
    return {real("restitution", "1", "", "normal restitution e against the wall (constant law)", 0,
                 1, true, false),
            choice("restitution_law", "constant", {"constant", "mcnamara_falcon", "viscoelastic"},
                   "normal restitution law at the wall, of the impact speed |v_n - u| relative to "
                   "the wall"),
            optional(mcnamara_falcon_r0_spec("")), optional(mcnamara_falcon_v0_spec()),
            optional(viscoelastic_gamma_spec())};
}

// How the keys of wall_restitution_schema() combine, for the wall drivers' descriptions
// (docs/scene-reference.md).
inline constexpr const char* kWallRestitutionDescription =
    R"md(
A wall moving with velocity u reflects a particle by v_n' - u = -e (v_n - u) (u = 0 for static
walls). The restitution e is the constant `restitution` (with `restitution_law: constant`), or a
function of the impact speed |v_n - u|, as the pair laws of the same names: `mcnamara_falcon` takes
`r0` (e at the yield velocity v0) and `v0`, `viscoelastic` takes `gamma` (the gamma of the
series).)md";

inline ImpactRestitution read_wall_restitution(const Params& p) {
    const std::string law = p.str("restitution_law");
    auto need = [&p, &law](const char* key) {
        if (!p.has(key)) p.fail("restitution_law", "law '" + law + "' needs `" + key + "`");
        return p.real(key);
    };
    if (law == "mcnamara_falcon") return mcnamara_falcon_impact_restitution(need("r0"), need("v0"));
    if (law == "viscoelastic") return viscoelastic_impact_restitution(need("gamma"));
    return constant_impact_restitution(p.real("restitution"));
}

}  // namespace gran
