#pragma once
// Impact-velocity-dependent coefficients of normal restitution for hard-particle collisions, as
// plain functions on plain data: the kernels of the laws `mcnamara_falcon` and `viscoelastic`
// (species/mcnamara_falcon.cpp, species/viscoelastic.cpp), evaluated once per collision.
//
// Convention (as in collision_rules.hpp): the coefficient e relates the normal components of the
// relative velocity at contact before and after the collision, g_n' = -e g_n. The impact speed is
// v = |g_n| = |(v1 - v2).n| for a pair and v = |(v - u_wall).n| for a wall (McNamara & Falcon 2005
// treat wall collisions "in the same way as collisions between particles, except the wall has
// infinite mass"). Speeds are in the engine's velocity unit: the paper constants below are SI and
// must be converted to the scene's units by the caller.
//
// Laws:
//   constant         e = e_const.
//   mcnamara_falcon  McNamara & Falcon, Phys. Rev. E 71, 031302 (2005), Eq. (1).
//   viscoelastic     Schwager & Poeschel, Phys. Rev. E 57, 650 (1998); Ramirez, Poeschel,
//                    Brilliantov & Schwager, Phys. Rev. E 60, 4465 (1999): the small-velocity
//                    series of viscoelastic (Hertz + dissipative) spheres, to order v^{2/5}.
#include <algorithm>
#include <cmath>
#include <limits>

namespace gran {

// ---------------------------------------------------------------------------------------------
// McNamara & Falcon 2005, Sec. II A, Eq. (1): viscoelastic regime at low impact speed joined to
// the plastic regime at high impact speed "as simply as possible",
//
//            { 1 - (1 - r0) (v / v0)^{1/5},   v <= v0,
//     r(v) = {
//            { r0 (v / v0)^{-1/4},            v >= v0,
//
// "where v0 = 0.3 m/s is chosen, throughout the paper, to be the yielding velocity for stainless
// steel particles [14, 25] for which r0 is close to 0.95 [25]".
//
// Properties that follow from Eq. (1) (tested in tests/species/test_impact_restitution.cpp):
//   r(0) = 1; r(v0) = r0 from both branches (continuous); r -> 0 as v -> infinity (like v^{-1/4},
//   NOT r -> r0); strictly decreasing; the slope jumps at v0 from -(1 - r0)/(5 v0) to
//   -r0/(4 v0), i.e. r(v) is continuous but not differentiable there. With the paper's values,
//   r(1 m/s) = 0.95 * 0.3^{1/4} = 0.7031, the "r(1 m/s) ~ 0.7 (see Fig. 1)" of Sec. III A.
// The low-speed branch is the first-order viscoelastic law below with
// gamma = (1 - r0) / (C1 v0^{1/5}).

inline constexpr double kMcNamaraFalconR0 = 0.95;  // r0, dimensionless (stainless steel, Ref. [25])
inline constexpr double kMcNamaraFalconV0 = 0.3;   // v0 in m/s (yield velocity, Refs. [14, 25])

// Eq. (1). v >= 0 is the normal impact speed, r0 in [0, 1], v0 > 0 in the same unit as v.
inline double mcnamara_falcon_restitution(double v, double r0, double v0) {
    const double u = v / v0;
    // Both branches are evaluated so that the selection can compile to a conditional move: the
    // comparison u <= 1 is not predictable in a gas whose typical speed is near v0.
    const double viscoelastic = 1.0 - (1.0 - r0) * std::pow(u, 0.2);  // v <= v0
    const double plastic = r0 / std::sqrt(std::sqrt(u));              // v >= v0: u^{-1/4}
    return u <= 1.0 ? viscoelastic : plastic;
}

// ---------------------------------------------------------------------------------------------
// Viscoelastic spheres (Brilliantov, Spahn, Hertzsch & Poeschel, Phys. Rev. E 53, 5382 (1996)):
// the normal force is F = rho (xi^{3/2} + (3/2) A xi^{1/2} xi'), rho = 2 Y sqrt(R_eff) /
// (3 (1 - nu^2)), with compression xi, Young modulus Y, Poisson ratio nu, R_eff = R1 R2/(R1 + R2),
// m_eff = m1 m2/(m1 + m2) and the dissipative constant A (a time). Integrating the contact gives
// (Schwager & Poeschel 1998; Ramirez et al. 1999, where the series is written
// epsilon = 1 - gamma_1 g^{1/5} + gamma_2 g^{2/5} -+ ...)
//
//     e(v) = 1 - C1 A kappa^{2/5} v^{1/5} + C2 A^2 kappa^{4/5} v^{2/5} -+ ...,
//     kappa = (3/2)^{3/2} Y sqrt(R_eff) / (m_eff (1 - nu^2)),
//     C1 = Gamma(3/5) sqrt(pi) / (2^{1/5} 5^{2/5} Gamma(21/10)) = 1.1534489 (printed 1.15344),
//     C2 = (3/5) C1^2 = 0.7982666 (printed 0.79826).
//
// The prefactor of kappa and both constants are checked independently by the test, which
// integrates the contact equation: what remains after the C2 term is O(x^{5/2}). (A polynomial
// extrapolation of such integrations to x -> 0 gives C2 = 0.798267.)
//
// Parameterisation: the law depends on the material only through gamma = A kappa^{2/5}, unit
// (time/length)^{1/5}; with x = gamma v^{1/5},
//
//     e(v) = 1 - C1 x + C2 x^2.
//
// Only the terms through v^{2/5} are implemented: C1 and C2 are the coefficients we can cite and
// check (the test integrates the contact equation and recovers both). Beyond v^{2/5} the series
// depends on when the collision is taken to end: ending it when the force vanishes (it would turn
// attractive) gives a next term in x^{5/2}, i.e. a power v^{1/2}; ending it when xi returns to 0
// gives x^3 instead (found by integrating the contact). No higher coefficient is used here.
//
// Range of validity (x = gamma v^{1/5}): compared with the direct integration of the contact
// (collision ending when the force vanishes) the two-term series is within 3e-4 for x <= 0.2
// (e >= 0.80) and within 4e-3 for x <= 0.3 (e >= 0.73); at x = 0.5 it is 0.03 too high. The
// truncated series has its minimum 1 - C1^2/(4 C2) = 7/12 at x = C1/(2 C2) = 5/(6 C1) = 0.7225
// and rises again beyond, which is unphysical: x is therefore clamped to [0, 5/(6 C1)], so that
// e is non-increasing in v for all v and lies in [7/12, 1] (inside [0, 1] by construction).
// Physically, the model also assumes quasi-static Hertz contact (v much below the speed of sound)
// and no plastic yield (v below the yield velocity, ~0.1-0.3 m/s for steel per McNamara & Falcon
// 2005), and it is a result for spheres (3D); for disks it is a phenomenological law.

inline constexpr double kViscoelasticC1 = 1.1534488580952884;  // closed form above
inline constexpr double kViscoelasticC2 = 0.6 * kViscoelasticC1 * kViscoelasticC1;
// x beyond which the two-term series would increase again: C1 / (2 C2) = 5 / (6 C1).
inline constexpr double kViscoelasticTurningX = kViscoelasticC1 / (2.0 * kViscoelasticC2);
// Documented validity of the two-term series (error <= 4e-3, see above).
inline constexpr double kViscoelasticValidX = 0.3;

// e(v) = 1 - C1 x + C2 x^2, x = gamma v^{1/5} clamped to [0, 5/(6 C1)]. v >= 0, gamma >= 0.
inline double viscoelastic_restitution(double v, double gamma) {
    const double x = std::clamp(gamma * std::pow(v, 0.2), 0.0, kViscoelasticTurningX);
    return 1.0 + x * (kViscoelasticC2 * x - kViscoelasticC1);
}

// gamma = A kappa^{2/5}, kappa = (3/2)^{3/2} Y sqrt(R_eff) / (m_eff (1 - nu^2)). Consistent units
// (SI: A in s, Y in Pa, R_eff in m, m_eff in kg; gamma in s^{1/5} m^{-1/5}).
inline double viscoelastic_gamma(double dissipative_time_a, double young_modulus,
                                 double poisson_ratio, double r_eff, double m_eff) {
    const double kappa = std::pow(1.5, 1.5) * young_modulus * std::sqrt(r_eff) /
                         (m_eff * (1.0 - poisson_ratio * poisson_ratio));
    return dissipative_time_a * std::pow(kappa, 0.4);
}

// gamma from one measured point e(v_ref) = e_ref: the smaller root of C2 x^2 - C1 x + 1 - e_ref = 0
// written without cancellation, x = 2 (1 - e_ref) / (C1 + sqrt(C1^2 - 4 C2 (1 - e_ref))), then
// gamma = x / v_ref^{1/5}. NaN unless 7/12 <= e_ref <= 1 and v_ref > 0; prefer e_ref >= 0.73
// (x <= 0.3), where the series is accurate.
inline double viscoelastic_gamma_from_reference(double e_ref, double v_ref) {
    const double d = 1.0 - e_ref;
    const double disc = kViscoelasticC1 * kViscoelasticC1 - 4.0 * kViscoelasticC2 * d;
    if (!(d >= 0.0 && disc >= 0.0 && v_ref > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    return 2.0 * d / (kViscoelasticC1 + std::sqrt(disc)) / std::pow(v_ref, 0.2);
}

// Impact speed up to which the series is used inside its documented validity: x(v) = x_valid.
inline double viscoelastic_max_valid_speed(double gamma, double x_valid = kViscoelasticValidX) {
    return std::pow(x_valid / gamma, 5.0);
}

}  // namespace gran
