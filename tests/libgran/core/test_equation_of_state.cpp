// Equation of state of inelastic hard-sphere mixtures (Barrat & Trizac 2002, Eq. (4)) against its
// special cases: Eq. (7) for one species in 2D, the elastic virial pressure n T (1 + 2^(d-1) phi
// chi) for one species in 3D, and splitting a species into two identical ones.
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/core/kinetic_theory.hpp"

namespace gran::theory {
namespace {

TEST(EquationOfState, OneSpeciesIn2DIsEquation7) {
    const double n = 0.05, T = 1.7, alpha = 0.8, phi = n * M_PI / 4;
    const double chi = contact_value_henderson_2d(phi);
    const double p = enskog_pressure(2, {n}, {T}, {2.0}, {1.0}, {alpha}, {chi});
    EXPECT_NEAR(p, n * T * (1 + (1 + alpha) * phi * chi), 1e-14);
}

TEST(EquationOfState, ElasticSpheresGiveTheVirialPressure) {
    const double n = 0.4, T = 1.0, phi = n * M_PI / 6;
    const double chi = contact_value_carnahan_starling(phi);
    const double p = enskog_pressure(3, {n}, {T}, {1.0}, {1.0}, {1.0}, {chi});
    EXPECT_NEAR(p / (n * T), 1 + 4 * phi * chi, 1e-13);
}

TEST(EquationOfState, SplittingASpeciesIntoTwoIdenticalHalvesChangesNothing) {
    const double n = 0.1, T = 0.9, alpha = 0.7, chi = 1.2;
    const double one = enskog_pressure(2, {n}, {T}, {1.0}, {1.0}, {alpha}, {chi});
    const double two = enskog_pressure(2, {n / 2, n / 2}, {T, T}, {1.0, 1.0}, {1.0, 1.0},
                                       {alpha, alpha, alpha, alpha}, {chi, chi, chi, chi});
    EXPECT_NEAR(one, two, 1e-15);
}

}  // namespace
}  // namespace gran::theory
