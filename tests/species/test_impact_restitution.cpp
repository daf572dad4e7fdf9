// Impact-velocity-dependent restitution: McNamara & Falcon 2005 Eq. (1), the viscoelastic series
// of Schwager & Poeschel 1998 / Ramirez et al. 1999 (checked against a direct integration of the
// viscoelastic Hertz contact), and the per-collision dispatcher.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <vector>

#include "species/impact_restitution.hpp"

namespace gran {
namespace {

constexpr double kR0 = kMcNamaraFalconR0;
constexpr double kV0 = kMcNamaraFalconV0;

double mf(double v) {
    return mcnamara_falcon_restitution(v, kR0, kV0);
}

// Logarithmic grid of n points from a to b.
std::vector<double> log_grid(double a, double b, int n) {
    std::vector<double> v;
    for (int i = 0; i < n; ++i) v.push_back(a * std::pow(b / a, i / double(n - 1)));
    return v;
}

// ----- McNamara & Falcon 2005, Eq. (1) -------------------------------------------------------

TEST(McNamaraFalconRestitution, PaperParameters) {
    EXPECT_EQ(kMcNamaraFalconR0, 0.95);  // Sec. II A: r0 close to 0.95 for stainless steel
    EXPECT_EQ(kMcNamaraFalconV0, 0.3);   // Sec. II A: v0 = 0.3 m/s
}

TEST(McNamaraFalconRestitution, ContinuousAtV0) {
    EXPECT_NEAR(mf(kV0), kR0, 1e-15);
    // Both branches of Eq. (1) give r0 at v = v0.
    EXPECT_NEAR(1.0 - (1.0 - kR0) * std::pow(1.0, 0.2), kR0, 1e-15);
    EXPECT_NEAR(kR0 * std::pow(1.0, -0.25), kR0, 1e-15);
    for (double eps : {1e-6, 1e-9, 1e-12}) {
        EXPECT_NEAR(mf(kV0 * (1 - eps)), kR0, 2 * eps);
        EXPECT_NEAR(mf(kV0 * (1 + eps)), kR0, 2 * eps);
    }
}

TEST(McNamaraFalconRestitution, SlopeJumpsAtV0) {
    // Eq. (1) is continuous but not differentiable at v0: dr/dv = -(1 - r0)/(5 v0) from below and
    // -r0/(4 v0) from above (-1/30 and -0.7917 s/m with the paper's values).
    const double h = 1e-7 * kV0;
    const double left = (mf(kV0) - mf(kV0 - h)) / h;
    const double right = (mf(kV0 + h) - mf(kV0)) / h;
    EXPECT_NEAR(left, -(1 - kR0) / (5 * kV0), 1e-6);
    EXPECT_NEAR(right, -kR0 / (4 * kV0), 1e-5);
}

TEST(McNamaraFalconRestitution, ElasticAtLowSpeed) {
    EXPECT_EQ(mf(0.0), 1.0);
    // 1 - r = (1 - r0)(v/v0)^{1/5} -> 0, slowly: 5e-4 at v = 1e-10 v0.
    EXPECT_NEAR(mf(1e-10 * kV0), 1 - 0.05 * 0.01, 1e-15);
    double prev = 0;
    for (double v : log_grid(1e-12 * kV0, kV0, 25)) {
        const double loss = 1 - mf(v);
        EXPECT_GT(loss, prev);
        prev = loss;
    }
}

TEST(McNamaraFalconRestitution, FullyInelasticAtHighSpeedNotR0) {
    // r = r0 (v/v0)^{-1/4} -> 0 as v -> infinity; r0 is the value at v0, not a plateau.
    EXPECT_NEAR(mf(1e8 * kV0), 0.95 * 0.01, 1e-15);
    EXPECT_LT(mf(1e4 * kV0), 0.1 * kR0 + 1e-15);
    EXPECT_GT(mf(1e12 * kV0), 0.0);
}

TEST(McNamaraFalconRestitution, HandComputedValues) {
    // (1/32)^{1/5} = 1/2, (1/243)^{1/5} = 1/3, 16^{-1/4} = 1/2, 81^{-1/4} = 1/3.
    EXPECT_NEAR(mf(kV0 / 32), 1 - 0.05 / 2, 1e-15);  // v = 9.375 mm/s: 0.975
    EXPECT_NEAR(mf(kV0 / 243), 1 - 0.05 / 3, 1e-15);
    EXPECT_NEAR(mf(16 * kV0), 0.95 / 2, 1e-15);  // v = 4.8 m/s: 0.475
    EXPECT_NEAR(mf(81 * kV0), 0.95 / 3, 1e-15);
    // Other parameters: r0 = 0.7, v0 = 2 (any unit).
    EXPECT_NEAR(mcnamara_falcon_restitution(2.0 / 32, 0.7, 2.0), 1 - 0.3 / 2, 1e-15);
    EXPECT_NEAR(mcnamara_falcon_restitution(32.0, 0.7, 2.0), 0.7 / 2, 1e-15);
}

TEST(McNamaraFalconRestitution, OneMetrePerSecondIsAboutPointSeven) {
    // Sec. III A: "r = r(1 m/s) ~ 0.7 (see Fig. 1)". Eq. (1): 0.95 * 0.3^{1/4} = 0.70306.
    EXPECT_NEAR(mf(1.0), 0.95 * std::pow(0.3, 0.25), 1e-15);
    EXPECT_NEAR(mf(1.0), 0.7, 0.005);
}

TEST(McNamaraFalconRestitution, StrictlyDecreasing) {
    double prev = 1.0 + 1e-12;
    for (double v : log_grid(1e-9 * kV0, 1e9 * kV0, 400)) {
        const double r = mf(v);
        EXPECT_LT(r, prev) << "v = " << v;
        EXPECT_GT(r, 0.0);
        EXPECT_LE(r, 1.0);
        prev = r;
    }
}

TEST(McNamaraFalconRestitution, LowSpeedBranchIsFirstOrderViscoelastic) {
    // 1 - r = (1 - r0)(v/v0)^{1/5} = C1 gamma v^{1/5} with gamma = (1 - r0)/(C1 v0^{1/5}).
    const double gamma = (1 - kR0) / (kViscoelasticC1 * std::pow(kV0, 0.2));
    for (double v : log_grid(1e-6 * kV0, kV0, 7)) {
        EXPECT_NEAR(1 - mf(v), kViscoelasticC1 * gamma * std::pow(v, 0.2), 1e-15);
    }
}

// ----- Viscoelastic series -------------------------------------------------------------------

// Direct integration of the viscoelastic Hertz contact (Brilliantov et al. 1996) in the units
// xi = L s, t = (L/g) tau, L = (g^2 m_eff/rho)^{2/5}: s'' = -(s^{3/2} + (3/2) b s^{1/2} s'),
// s(0) = 0, s'(0) = 1, with b = A (rho/m_eff)^{2/5} g^{1/5}. The collision ends when the force
// vanishes (it would turn attractive); e = -s'(end). RK4, linear interpolation of the end.
double contact_restitution(double b, double h = 1e-5) {
    struct State {
        double s, u;
    };
    auto force = [b](const State& y) {
        const double s = y.s > 0 ? y.s : 0;
        return s * std::sqrt(s) + 1.5 * b * std::sqrt(s) * y.u;
    };
    auto rhs = [&](const State& y) { return State{y.u, -force(y)}; };
    State y{0, 1};
    for (long step = 0; step < 100000000L; ++step) {
        const State k1 = rhs(y);
        const State k2 = rhs({y.s + 0.5 * h * k1.s, y.u + 0.5 * h * k1.u});
        const State k3 = rhs({y.s + 0.5 * h * k2.s, y.u + 0.5 * h * k2.u});
        const State k4 = rhs({y.s + h * k3.s, y.u + h * k3.u});
        const State next{y.s + h / 6 * (k1.s + 2 * k2.s + 2 * k3.s + k4.s),
                         y.u + h / 6 * (k1.u + 2 * k2.u + 2 * k3.u + k4.u)};
        const double f0 = force(y), f1 = force(next);
        if (next.u < 0 && f1 <= 0) {
            const double w = f0 / (f0 - f1);
            return -(y.u + w * (next.u - y.u));
        }
        y = next;
    }
    return std::numeric_limits<double>::quiet_NaN();
}

double series(double x) {
    return 1 - kViscoelasticC1 * x + kViscoelasticC2 * x * x;
}

TEST(ViscoelasticRestitution, Constants) {
    // C1 = Gamma(3/5) sqrt(pi) / (2^{1/5} 5^{2/5} Gamma(21/10)); C2 = (3/5) C1^2.
    const double c1 = std::tgamma(0.6) * std::sqrt(std::numbers::pi) /
                      (std::pow(2.0, 0.2) * std::pow(5.0, 0.4) * std::tgamma(2.1));
    EXPECT_NEAR(kViscoelasticC1, c1, 1e-15);
    EXPECT_NEAR(kViscoelasticC1, 1.15344, 1e-5);  // as printed in the literature
    EXPECT_NEAR(kViscoelasticC2, 0.79826, 1e-5);
    EXPECT_NEAR(kViscoelasticTurningX, 5.0 / (6.0 * c1), 1e-15);
}

TEST(ViscoelasticRestitution, ElasticAtLowSpeed) {
    EXPECT_EQ(viscoelastic_restitution(0.0, 0.1), 1.0);
    EXPECT_EQ(viscoelastic_restitution(5.0, 0.0), 1.0);  // gamma = 0: elastic
    // 1 - e = C1 x - C2 x^2 with x = gamma v^{1/5}.
    const double gamma = 0.1;
    for (double v : log_grid(1e-15, 1e-5, 6)) {
        const double x = gamma * std::pow(v, 0.2);
        EXPECT_NEAR(1 - viscoelastic_restitution(v, gamma), kViscoelasticC1 * x, 2 * x * x);
    }
}

TEST(ViscoelasticRestitution, HandComputedValues) {
    // gamma = 0.1, v = 32: x = 0.2, e = 1 - 0.230689772 + 0.031930662 = 0.801240891.
    EXPECT_NEAR(viscoelastic_restitution(32.0, 0.1), 0.801240891, 1e-9);
    // gamma = 0.05, v = 1: x = 0.05, e = 1 - 0.057672443 + 0.001995666 = 0.944323223.
    EXPECT_NEAR(viscoelastic_restitution(1.0, 0.05), 0.944323223, 1e-9);
    // gamma = 0.3, v = 1/243: x = 0.1, e = 1 - 0.115344886 + 0.007982666 = 0.892637780.
    EXPECT_NEAR(viscoelastic_restitution(1.0 / 243, 0.3), 0.892637780, 1e-9);
}

TEST(ViscoelasticRestitution, MatchesContactIntegrationThroughSecondOrder) {
    // x = gamma v^{1/5} = (3/2) b. The residual after the C2 term is O(x^{5/2}): a wrong C2 (e.g.
    // 0.0798) would leave 7e-5 at x = 0.01, against 2e-6 observed.
    for (double x : {0.005, 0.01, 0.02, 0.05, 0.1}) {
        const double exact = contact_restitution(x / 1.5);
        EXPECT_NEAR(exact, series(x), 0.5 * std::pow(x, 2.5)) << "x = " << x;
    }
    // Documented accuracy of the two-term series.
    for (double x : {0.12, 0.15, 0.2}) EXPECT_NEAR(contact_restitution(x / 1.5), series(x), 3e-4);
    EXPECT_NEAR(contact_restitution(0.3 / 1.5), series(0.3), 4e-3);
}

TEST(ViscoelasticRestitution, MaterialGammaMatchesContactEquation) {
    // Steel-like spheres of radius 1 mm: Y = 2e11 Pa, nu = 0.3, density 7800 kg/m^3, A = 1e-7 s.
    const double radius = 1e-3, mass = 7800 * 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3);
    const double r_eff = radius / 2, m_eff = mass / 2, young = 2e11, nu = 0.3, a = 1e-7;
    const double gamma = viscoelastic_gamma(a, young, nu, r_eff, m_eff);
    const double rho = 2 * young * std::sqrt(r_eff) / (3 * (1 - nu * nu));  // Hertz constant
    for (double g : {0.01, 0.1, 1.0}) {
        const double b = a * std::pow(rho / m_eff, 0.4) * std::pow(g, 0.2);
        EXPECT_NEAR(gamma * std::pow(g, 0.2), 1.5 * b, 1e-12);
        EXPECT_NEAR(viscoelastic_restitution(g, gamma), contact_restitution(b), 3e-4);
    }
}

TEST(ViscoelasticRestitution, GammaFromReferencePoint) {
    for (double gamma : {0.01, 0.1, 0.3}) {
        for (double v : {0.01, 1.0, 50.0}) {
            const double e = viscoelastic_restitution(v, gamma);
            if (gamma * std::pow(v, 0.2) > kViscoelasticValidX) continue;
            EXPECT_NEAR(viscoelastic_gamma_from_reference(e, v), gamma, 1e-12 * (1 + gamma));
        }
    }
    EXPECT_EQ(viscoelastic_gamma_from_reference(1.0, 2.0), 0.0);
    EXPECT_TRUE(std::isnan(viscoelastic_gamma_from_reference(0.5, 1.0)));  // below 7/12
    EXPECT_TRUE(std::isnan(viscoelastic_gamma_from_reference(1.1, 1.0)));
    EXPECT_TRUE(std::isnan(viscoelastic_gamma_from_reference(0.9, 0.0)));
}

TEST(ViscoelasticRestitution, DecreasingOnValidityRangeAndBoundedBeyond) {
    const double gamma = 0.2;
    const double vmax = viscoelastic_max_valid_speed(gamma);
    EXPECT_NEAR(gamma * std::pow(vmax, 0.2), kViscoelasticValidX, 1e-14);
    double prev = 1.0 + 1e-12;
    for (double v : log_grid(1e-12 * vmax, vmax, 200)) {
        const double e = viscoelastic_restitution(v, gamma);
        EXPECT_LT(e, prev) << "v = " << v;
        prev = e;
    }
    EXPECT_GT(prev, 0.72);  // e(x = 0.3) = 0.7258
    // Beyond the validity range: non-increasing, saturating at the series minimum 7/12 from
    // x = 5/(6 C1) on, never negative or above 1.
    for (double v : log_grid(vmax, 1e12 * vmax, 200)) {
        const double e = viscoelastic_restitution(v, gamma);
        EXPECT_LE(e, prev);
        EXPECT_GE(e, 7.0 / 12.0 - 1e-15);
        prev = e;
    }
    EXPECT_NEAR(prev, 7.0 / 12.0, 1e-15);
}

}  // namespace
}  // namespace gran
