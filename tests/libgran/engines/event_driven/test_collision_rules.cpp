// Binary collision rules against the closed forms of Barrat & Trizac 2002 (Eqs. 1-3, Appendix A).
#include <gtest/gtest.h>

#include <random>

#include "libgran/engines/event_driven/collision_rules.hpp"

namespace gran {
namespace {

template <int D>
Vec<D> random_vec(std::mt19937_64& g) {
    std::normal_distribution<double> n;
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = n(g);
    return v;
}

template <int D>
AngVec<D> random_ang(std::mt19937_64& g) {
    std::normal_distribution<double> n;
    if constexpr (D == 2) {
        return n(g);
    } else {
        return Eigen::Vector3d(n(g), n(g), n(g));
    }
}

// Angular-momentum-like quantity for conservation checks: r x p as an AngVec.
template <int D>
AngVec<D> cross_rp(const Vec<D>& r, const Vec<D>& p) {
    return cross_n<D>(r, p);
}

template <int D>
void check_smooth(double alpha) {
    std::mt19937_64 g(11);
    for (int trial = 0; trial < 200; ++trial) {
        const double m1 = 0.5 + std::uniform_real_distribution<double>(0, 5)(g);
        const double m2 = 0.5 + std::uniform_real_distribution<double>(0, 5)(g);
        Vec<D> n = random_vec<D>(g).normalized();
        Vec<D> v1 = random_vec<D>(g), v2 = random_vec<D>(g);
        if ((v1 - v2).dot(n) > 0) n = -n;  // approaching
        const Vec<D> p0 = m1 * v1 + m2 * v2;
        const double e0 = 0.5 * m1 * v1.squaredNorm() + 0.5 * m2 * v2.squaredNorm();
        const double gn = (v1 - v2).dot(n);
        const Vec<D> gt = (v1 - v2) - gn * n;
        Vec<D> a = v1, b = v2;
        const double impulse = smooth_collision<D>(a, b, m1, m2, n, alpha);
        const double mu = m1 * m2 / (m1 + m2);
        EXPECT_LT((m1 * a + m2 * b - p0).norm(), 1e-13 * (1 + p0.norm()));
        EXPECT_NEAR((a - b).dot(n), -alpha * gn, 1e-13);               // Eq. (1)-(2)
        EXPECT_LT(((a - b) - (a - b).dot(n) * n - gt).norm(), 1e-13);  // tangential untouched
        EXPECT_NEAR(impulse, -mu * (1 + alpha) * gn, 1e-12);           // Eq. (3)
        const double e1 = 0.5 * m1 * a.squaredNorm() + 0.5 * m2 * b.squaredNorm();
        EXPECT_NEAR(e1 - e0, collision_energy_change(mu, 0, gn * gn, 0, alpha, -1),
                    1e-12 * (1 + e0));
    }
}

TEST(SmoothCollision, DisksConserveMomentumReverseNormalVelocityAndLoseClosedFormEnergy) {
    check_smooth<2>(0.7);
}
TEST(SmoothCollision, SpheresConserveMomentumReverseNormalVelocityAndLoseClosedFormEnergy) {
    check_smooth<3>(0.7);
}
TEST(SmoothCollision, ElasticLimitConservesEnergyExactly) {
    check_smooth<2>(1.0);
    check_smooth<3>(1.0);
}

template <int D>
void check_rough(double alpha, double beta, double q1, double q2) {
    std::mt19937_64 g(12);
    for (int trial = 0; trial < 200; ++trial) {
        const double m1 = 0.5 + std::uniform_real_distribution<double>(0, 5)(g);
        const double m2 = 0.5 + std::uniform_real_distribution<double>(0, 5)(g);
        const double s1 = 0.5 + std::uniform_real_distribution<double>(0, 2)(g);
        const double s2 = 0.5 + std::uniform_real_distribution<double>(0, 2)(g);
        Vec<D> n = random_vec<D>(g).normalized();
        Vec<D> v1 = random_vec<D>(g), v2 = random_vec<D>(g);
        if ((v1 - v2).dot(n) > 0) n = -n;
        AngVec<D> w1 = random_ang<D>(g), w2 = random_ang<D>(g);
        const double I1 = q1 * m1 * s1 * s1 / 4, I2 = q2 * m2 * s2 * s2 / 4;
        // Contact geometry: r1 - r2 = n (s1 + s2)/2; place r2 at the origin.
        const Vec<D> r1 = 0.5 * (s1 + s2) * n, r2 = Vec<D>::Zero();
        auto contact_velocity = [&](const Vec<D>& a, const Vec<D>& b, const AngVec<D>& wa,
                                    const AngVec<D>& wb) {
            // Eq. (A2)
            return Vec<D>(a - b - cross_w<D>(AngVec<D>(0.5 * s1 * wa + 0.5 * s2 * wb), n));
        };
        const Vec<D> gv = contact_velocity(v1, v2, w1, w2);
        const double gn = gv.dot(n);
        const Vec<D> gt = gv - gn * n;
        auto energy = [&](const Vec<D>& a, const Vec<D>& b, const AngVec<D>& wa,
                          const AngVec<D>& wb) {
            return 0.5 * m1 * a.squaredNorm() + 0.5 * m2 * b.squaredNorm() +
                   0.5 * I1 * ang_squared<D>(wa) + 0.5 * I2 * ang_squared<D>(wb);
        };
        auto angmom = [&](const Vec<D>& a, const Vec<D>& b, const AngVec<D>& wa,
                          const AngVec<D>& wb) {
            return AngVec<D>(cross_rp<D>(r1, m1 * a) + cross_rp<D>(r2, m2 * b) + I1 * wa + I2 * wb);
        };
        const double e0 = energy(v1, v2, w1, w2);
        const AngVec<D> l0 = angmom(v1, v2, w1, w2);
        const Vec<D> p0 = m1 * v1 + m2 * v2;
        Vec<D> a = v1, b = v2;
        AngVec<D> wa = w1, wb = w2;
        rough_collision<D>(a, b, wa, wb, m1, m2, s1, s2, q1, q2, n, alpha, beta);
        const Vec<D> g1 = contact_velocity(a, b, wa, wb);
        EXPECT_LT((m1 * a + m2 * b - p0).norm(), 1e-12 * (1 + p0.norm()));
        EXPECT_NEAR(g1.dot(n), -alpha * gn, 1e-12);                 // Eq. (A8)
        EXPECT_LT((g1 - g1.dot(n) * n + beta * gt).norm(), 1e-12);  // Eq. (A9)
        if constexpr (D == 2) {
            EXPECT_NEAR(angmom(a, b, wa, wb), l0, 1e-11);
        } else {
            EXPECT_LT((angmom(a, b, wa, wb) - l0).norm(), 1e-11);
        }
        const double mu = m1 * m2 / (m1 + m2);
        const double mu_t = 1.0 / (1 / m1 + 1 / m2 + 1 / (q1 * m1) + 1 / (q2 * m2));
        EXPECT_NEAR(energy(a, b, wa, wb) - e0,
                    collision_energy_change(mu, mu_t, gn * gn, gt.squaredNorm(), alpha, beta),
                    1e-11 * (1 + e0));
    }
}

TEST(RoughCollision, DisksSatisfyAppendixARules) {
    check_rough<2>(0.8, 0.3, 0.5, 0.5);
}
TEST(RoughCollision, SpheresSatisfyAppendixARules) {
    check_rough<3>(0.8, -0.5, 0.4, 0.4);
}
TEST(RoughCollision, UnequalInertiaFactorsSatisfyTheSameRules) {
    check_rough<3>(0.9, 0.5, 0.3, 0.66);
}
TEST(RoughCollision, BetaMinusOneIsTheSmoothRule) {
    Vec<3> v1(0.3, -1.2, 0.5), v2(-0.4, 0.9, 0.1), n = Vec<3>(1, 2, -0.5).normalized();
    if ((v1 - v2).dot(n) > 0) n = -n;
    Eigen::Vector3d w1(1, 2, 3), w2(-1, 0.5, 2);
    Vec<3> a = v1, b = v2, c = v1, d = v2;
    rough_collision<3>(a, b, w1, w2, 2.0, 1.0, 1.0, 1.0, 0.4, 0.4, n, 0.6, -1.0);
    smooth_collision<3>(c, d, 2.0, 1.0, n, 0.6);
    EXPECT_LT((a - c).norm(), 1e-14);
    EXPECT_LT((b - d).norm(), 1e-14);
    EXPECT_EQ(w1, Eigen::Vector3d(1, 2, 3));
}
// Eq. (A12) as printed, for equal masses factors q: P = -mu[(1+alpha) g_n + (1+beta)/(1+1/q) g_t].
TEST(RoughCollision, MatchesEquationA12ForEqualInertiaFactors) {
    const double m1 = 3, m2 = 1, q = 0.5, alpha = 0.85, beta = 0.2;
    Vec<2> v1(0.7, -0.2), v2(-0.5, 0.4), n = Vec<2>(-1, 0.3).normalized();
    double w1 = 1.3, w2 = -0.6;
    const Vec<2> g = v1 - v2 - cross_w<2>(0.5 * 1.0 * w1 + 0.5 * 1.0 * w2, n);
    const Vec<2> gn = g.dot(n) * n, gt = g - gn;
    const double mu = m1 * m2 / (m1 + m2);
    const Vec<2> P = -mu * ((1 + alpha) * gn + (1 + beta) / (1 + 1 / q) * gt);
    Vec<2> a = v1, b = v2;
    rough_collision<2>(a, b, w1, w2, m1, m2, 1.0, 1.0, q, q, n, alpha, beta);
    EXPECT_LT((m1 * (a - v1) - P).norm(), 1e-13);
}

}  // namespace
}  // namespace gran
