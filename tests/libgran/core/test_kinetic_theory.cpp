#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "libgran/core/kinetic_theory.hpp"

namespace gran::theory {
namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Independent reference implementations used by the tests.

// Energy rate written in the form it takes straight out of the derivation (not the rearranged
// bracket used by the library): with a = mu_ji (1+alpha) g.n and <v_i | g> = (T_i/m_i)/s2 g,
//   R_ij = n_j chi sigma^(d-1) B_3 <|g|^3> (m_i/2) mu_ji (1+alpha) [mu_ji (1+alpha) - 2 T_i/(m_i
//   s2)]
// with B_3 <|g|^3> = pi^((d-1)/2) Gamma(2)/Gamma((d+3)/2) * (2 s2)^(3/2) Gamma((d+3)/2)/Gamma(d/2).
double reference_energy_rate(int d, double n_j, double sigma_ij, double chi_ij, double alpha,
                             double Ti, double mi, double Tj, double mj) {
    const double dd = static_cast<double>(d);
    const double mu = mj / (mi + mj);
    const double s2 = Ti / mi + Tj / mj;
    const double b3 = std::pow(kPi, 0.5 * (dd - 1.0)) / std::tgamma(0.5 * (dd + 3.0));
    const double g3 =
        std::pow(2.0 * s2, 1.5) * std::tgamma(0.5 * (dd + 3.0)) / std::tgamma(0.5 * dd);
    return n_j * chi_ij * std::pow(sigma_ij, dd - 1.0) * b3 * g3 * 0.5 * mi * mu * (1.0 + alpha) *
           (mu * (1.0 + alpha) - 2.0 * Ti / (mi * s2));
}

struct SpeciesRates {
    double r1;  // sum_j R_1j
    double r2;  // sum_j R_2j
};

SpeciesRates reference_rates(const BinaryMixture& m, double T1, double T2) {
    const double s12 = 0.5 * (m.sigma1 + m.sigma2);
    return {reference_energy_rate(m.d, m.n1, m.sigma1, m.chi11, m.alpha11, T1, m.m1, T1, m.m1) +
                reference_energy_rate(m.d, m.n2, s12, m.chi12, m.alpha12, T1, m.m1, T2, m.m2),
            reference_energy_rate(m.d, m.n1, s12, m.chi12, m.alpha12, T2, m.m2, T1, m.m1) +
                reference_energy_rate(m.d, m.n2, m.sigma2, m.chi22, m.alpha22, T2, m.m2, T2, m.m2)};
}

// Relative residual of the heated steady state at T1 = 1, T2 = gamma: xi_1 from the balance of
// species 1, xi_2 from the noise convention, then the balance of species 2.
double heated_residual(const BinaryMixture& m, NoiseConvention conv, double gamma) {
    const SpeciesRates r = reference_rates(m, 1.0, gamma);
    const double dd = static_cast<double>(m.d);
    const double xi1_sq = -2.0 * r.r1 / (dd * m.m1);
    const double xi2_sq = conv == NoiseConvention::EqualVelocityVariance
                              ? xi1_sq
                              : xi1_sq * (m.m1 * m.m1) / (m.m2 * m.m2);
    const double heating2 = dd * m.m2 * xi2_sq / 2.0;
    return std::abs(r.r2 + heating2) / std::abs(r.r2);
}

// Relative residual of zeta_1 = zeta_2 at T1 = 1, T2 = gamma.
double hcs_residual(const BinaryMixture& m, double gamma) {
    const SpeciesRates r = reference_rates(m, 1.0, gamma);
    const double dd = static_cast<double>(m.d);
    const double zeta1 = -2.0 * r.r1 / (dd * 1.0);
    const double zeta2 = -2.0 * r.r2 / (dd * gamma);
    return std::abs(zeta1 - zeta2) / std::abs(zeta1);
}

// Equimolar dilute (chi = 1) mixture of equal-size species, m2 = 1, m1 = mass_ratio.
BinaryMixture equal_size_mixture(int d, double mass_ratio, double alpha) {
    return BinaryMixture{d, mass_ratio, 1.0, 1.0, 1.0, 0.5, 0.5, alpha, alpha, alpha};
}

// ---------------------------------------------------------------------------------------------
// Contact values.

TEST(KineticTheory, UnitBallVolumeIsPiOver4In2DAndPiOver6In3D) {
    EXPECT_DOUBLE_EQ(unit_ball_volume(2), kPi / 4.0);
    EXPECT_DOUBLE_EQ(unit_ball_volume(3), kPi / 6.0);
    EXPECT_THROW(unit_ball_volume(1), std::invalid_argument);
    EXPECT_THROW(unit_ball_volume(4), std::invalid_argument);
}

TEST(KineticTheory, MonodisperseContactValuesAtKnownPoints) {
    EXPECT_DOUBLE_EQ(contact_value_henderson_2d(0.0), 1.0);
    EXPECT_DOUBLE_EQ(contact_value_carnahan_starling(0.0), 1.0);
    // (1 - 7/32) / (1/4) = 25/8.
    EXPECT_DOUBLE_EQ(contact_value_henderson_2d(0.5), 3.125);
    // (1 - 1/4) / (1/8) = 6.
    EXPECT_DOUBLE_EQ(contact_value_carnahan_starling(0.5), 6.0);
    // (1 - 0.7/16) / 0.81 = 0.95625 / 0.81; (1 - 0.05) / 0.729.
    EXPECT_DOUBLE_EQ(contact_value_henderson_2d(0.1), 0.95625 / 0.81);
    EXPECT_DOUBLE_EQ(contact_value_carnahan_starling(0.1), 0.95 / 0.729);
    EXPECT_DOUBLE_EQ(contact_value(2, 0.3), contact_value_henderson_2d(0.3));
    EXPECT_DOUBLE_EQ(contact_value(3, 0.3), contact_value_carnahan_starling(0.3));
    EXPECT_THROW(contact_value(3, 1.0), std::invalid_argument);
    EXPECT_THROW(contact_value(2, -0.1), std::invalid_argument);
    EXPECT_THROW(contact_value(4, 0.1), std::invalid_argument);
}

TEST(KineticTheory, MixtureContactValuesReduceToMonodisperseForEqualSizes) {
    const std::vector<double> x = {0.2, 0.5, 0.3};
    for (int d : {2, 3}) {
        for (double phi : {0.0, 0.1, 0.35, 0.6}) {
            for (double sigma : {0.5, 1.0, 3.0}) {
                const std::vector<double> chi =
                    contact_values_mixture(d, phi, {sigma, sigma, sigma}, x);
                ASSERT_EQ(chi.size(), 9u);
                for (double c : chi) EXPECT_NEAR(c, contact_value(d, phi), 1e-14) << d << phi;
            }
        }
    }
}

TEST(KineticTheory, MixtureContactValuesAtHandComputedPoint) {
    // sigma = {1, 2}, x = {1/2, 1/2}, phi = 0.3: z_ij = sigma_i sigma_j / sigma_ij times
    // <sigma^2>/<sigma^3> = 5/9 (3D) or <sigma>/<sigma^2> = 3/5 (2D).
    const std::vector<double> chi3 = contact_values_mixture(3, 0.3, {1.0, 2.0}, {0.5, 0.5});
    EXPECT_NEAR(chi3[0], 1.9792678976352447, 1e-13);
    EXPECT_NEAR(chi3[1], 2.180830003959256, 1e-13);
    EXPECT_NEAR(chi3[2], 2.180830003959256, 1e-13);
    EXPECT_NEAR(chi3[3], 2.6109491415613864, 1e-13);
    const std::vector<double> chi2 = contact_values_mixture(2, 0.3, {1.0, 2.0}, {0.5, 0.5});
    EXPECT_NEAR(chi2[0], 1.6352040816326532, 1e-13);
    EXPECT_NEAR(chi2[1], 1.7040816326530612, 1e-13);
    EXPECT_NEAR(chi2[3], 1.8418367346938775, 1e-13);
    // Fractions need not be normalised.
    const std::vector<double> chi3b = contact_values_mixture(3, 0.3, {1.0, 2.0}, {2.0, 2.0});
    for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(chi3b[k], chi3[k], 1e-14);
}

TEST(KineticTheory, MixtureContactValuesReproduceMixtureEquationOfStateByVirialRoute) {
    // Virial route: Z = 1 + (2^(d-1) V_d) n sum_ij x_i x_j sigma_ij^d chi_ij. With the BMCSL
    // contact values this must give the BMCSL equation of state (3D),
    //   Z = 1/(1-phi) + 3 phi <s><s^2>/(<s^3>(1-phi)^2) + phi^2 (3-phi) <s^2>^3/(<s^3>^2
    //   (1-phi)^3),
    // and in 2D the Santos-Yuste-Lopez de Haro EOS built on Henderson's Z_p,
    //   Z = 1/(1-phi) + (Z_p(phi) - 1/(1-phi)) <s>^2/<s^2>,  Z_p = 1 + 2 phi chi_Henderson(phi).
    const std::vector<double> s = {1.0, 2.3, 0.7};
    const std::vector<double> x = {0.2, 0.5, 0.3};
    auto moment = [&](int k) {
        double m = 0.0;
        for (std::size_t i = 0; i < s.size(); ++i) m += x[i] * std::pow(s[i], k);
        return m;
    };
    for (int d : {2, 3}) {
        for (double phi : {0.05, 0.2, 0.45}) {
            const double dd = static_cast<double>(d);
            const double n = phi / (unit_ball_volume(d) * moment(d));
            const std::vector<double> chi = contact_values_mixture(d, phi, s, x);
            double sum = 0.0;
            for (std::size_t i = 0; i < 3; ++i) {
                for (std::size_t j = 0; j < 3; ++j) {
                    sum += x[i] * x[j] * std::pow(0.5 * (s[i] + s[j]), dd) * chi[i * 3 + j];
                }
            }
            const double z_virial = 1.0 + std::pow(2.0, dd - 1.0) * unit_ball_volume(d) * n * sum;
            double z_eos = 0.0;
            if (d == 3) {
                z_eos = 1.0 / (1.0 - phi) +
                        3.0 * phi * moment(1) * moment(2) / (moment(3) * std::pow(1.0 - phi, 2)) +
                        phi * phi * (3.0 - phi) * std::pow(moment(2), 3) /
                            (std::pow(moment(3), 2) * std::pow(1.0 - phi, 3));
            } else {
                const double z_p = 1.0 + 2.0 * phi * contact_value_henderson_2d(phi);
                z_eos = 1.0 / (1.0 - phi) +
                        (z_p - 1.0 / (1.0 - phi)) * moment(1) * moment(1) / moment(2);
            }
            EXPECT_NEAR(z_virial, z_eos, 1e-12 * z_eos) << "d=" << d << " phi=" << phi;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Collision frequencies.

TEST(KineticTheory, CollisionFrequencyMatchesHandValues) {
    // 2D: 2 sqrt(pi) * 0.1 * 1 * 1.5 * sqrt(2/0.5) = 0.6 sqrt(pi).
    EXPECT_NEAR(enskog_collision_frequency(2, 0.1, 1.0, 1.5, 2.0, 0.5), 1.0634723105433095, 1e-14);
    // 3D: 4 sqrt(pi) * 0.2 * 2^2 * 1.2 * sqrt(1/4) = 1.92 sqrt(pi).
    EXPECT_NEAR(enskog_collision_frequency(3, 0.2, 2.0, 1.2, 1.0, 4.0), 3.40311139373859, 1e-13);
    // Pair frequency, 3D: pi/Gamma(3/2) = 2 sqrt(pi); 2 sqrt(pi) * 0.3 * 1.1 * 1.5^2 *
    // sqrt(2 (2/1 + 1/4)) = 1.485 sqrt(pi) sqrt(4.5).
    EXPECT_NEAR(enskog_pair_collision_frequency(3, 0.3, 1.5, 1.1, 2.0, 1.0, 1.0, 4.0),
                1.485 * std::sqrt(kPi * 4.5), 1e-13);
    // Pair frequency, 2D: sqrt(pi)/Gamma(1) = sqrt(pi); sqrt(pi) * 0.5 * 1.2 * 0.8 *
    // sqrt(2 (1/2 + 3/1.5)) = 0.48 sqrt(5 pi).
    EXPECT_NEAR(enskog_pair_collision_frequency(2, 0.5, 0.8, 1.2, 1.0, 2.0, 3.0, 1.5),
                0.48 * std::sqrt(5.0 * kPi), 1e-13);
}

TEST(KineticTheory, PairFrequencySummedOverIdenticalSpeciesEqualsMonodisperseFrequency) {
    for (int d : {2, 3}) {
        const double n = 0.37, sigma = 1.3, chi = 1.7, T = 2.2, m = 0.8;
        const double omega = enskog_collision_frequency(d, n, sigma, chi, T, m);
        for (double x1 : {0.5, 0.1, 0.9}) {
            const double nu =
                enskog_pair_collision_frequency(d, x1 * n, sigma, chi, T, m, T, m) +
                enskog_pair_collision_frequency(d, (1 - x1) * n, sigma, chi, T, m, T, m);
            EXPECT_NEAR(nu, omega, 1e-13 * omega);
        }
        // Collisions per volume balance: n_i nu_ij = n_j nu_ji.
        const double n1 = 0.2, n2 = 0.7;
        EXPECT_NEAR(n1 * enskog_pair_collision_frequency(d, n2, 1.1, 1.3, 1.0, 2.0, 3.0, 0.5),
                    n2 * enskog_pair_collision_frequency(d, n1, 1.1, 1.3, 3.0, 0.5, 1.0, 2.0),
                    1e-14);
    }
}

// ---------------------------------------------------------------------------------------------
// Haff's law.

TEST(KineticTheory, HaffLawTimeScaleAndDecay) {
    // t0 = 2 d / ((1 - alpha^2) omega0): 2D, alpha = 0.9, omega0 = 2 -> 4 / (0.19 * 2).
    EXPECT_NEAR(haff_time_scale(2, 0.9, 2.0), 4.0 / 0.38, 1e-13);
    EXPECT_NEAR(haff_time_scale(3, 0.5, 1.0), 6.0 / 0.75, 1e-13);
    EXPECT_THROW(haff_time_scale(2, 1.0, 1.0), std::invalid_argument);
    EXPECT_DOUBLE_EQ(haff_temperature(3.0, 2.0, 0.0), 3.0);
    EXPECT_DOUBLE_EQ(haff_temperature(3.0, 2.0, 2.0), 0.75);

    // T(t) solves dT/dt = 2 R(T)/d with the monodisperse energy rate R and omega ~ sqrt(T).
    for (int d : {2, 3}) {
        const double n = 0.05, sigma = 1.0, chi = contact_value(d, 0.2), m = 1.5, alpha = 0.8;
        const double T0 = 4.0;
        const double t0 =
            haff_time_scale(d, alpha, enskog_collision_frequency(d, n, sigma, chi, T0, m));
        for (double t : {0.0, 0.3 * t0, 5.0 * t0}) {
            const double h = 1e-4 * t0;
            const double dTdt =
                (haff_temperature(T0, t0, t + h) - haff_temperature(T0, t0, t - h)) / (2.0 * h);
            const double T = haff_temperature(T0, t0, t);
            const double R = energy_rate(d, n, sigma, chi, alpha, T, m, T, m);
            EXPECT_NEAR(dTdt, 2.0 * R / d, 1e-6 * std::abs(dTdt)) << "d=" << d << " t=" << t;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Energy exchange rate.

// Hand values of van Noije & Ernst's formula: at alpha = 0.5 the numerator is 4 and the
// denominator 73 + 56 d - 12 d - 52.5 + 3.75; a2 vanishes at alpha = 1 and 1/sqrt(2).
TEST(KineticTheory, WhiteNoiseSonineA2AtHandComputedPoints) {
    EXPECT_NEAR(theory::white_noise_sonine_a2(3, 0.5), 4.0 / 156.25, 1e-15);
    EXPECT_NEAR(theory::white_noise_sonine_a2(2, 0.5), 4.0 / 112.25, 1e-15);
    EXPECT_EQ(theory::white_noise_sonine_a2(3, 1.0), 0.0);
    // Homogeneous cooling state: 16 (0.1)(-0.62) / (9 + 48 - 0.9 * 25 + 30 * 0.1 * 0.81) in 2D.
    EXPECT_NEAR(theory::hcs_sonine_a2(2, 0.9), -0.992 / 36.93, 1e-14);
    EXPECT_NEAR(theory::hcs_sonine_a2(3, 0.5), 4.0 / 76.25, 1e-14);
    EXPECT_EQ(theory::hcs_sonine_a2(3, 1.0), 0.0);
    EXPECT_NEAR(theory::hcs_sonine_a2(2, std::sqrt(0.5)), 0.0, 1e-15);
    EXPECT_NEAR(theory::white_noise_sonine_a2(2, 1 / std::sqrt(2.0)), 0.0, 1e-15);
    EXPECT_LT(theory::white_noise_sonine_a2(3, 0.9), 0.0);
}

TEST(KineticTheory, EnergyRateLimits) {
    for (int d : {2, 3}) {
        // Elastic, equal temperatures: no net exchange even for unequal masses and sizes.
        EXPECT_NEAR(energy_rate(d, 0.3, 1.2, 1.4, 1.0, 1.7, 1.0, 1.7, 5.0), 0.0, 1e-15);
        // Monodisperse: R = -(1 - alpha^2) T omega / 2.
        const double n = 0.2, sigma = 0.9, chi = 1.3, alpha = 0.6, T = 2.5, m = 1.2;
        const double omega = enskog_collision_frequency(d, n, sigma, chi, T, m);
        EXPECT_NEAR(energy_rate(d, n, sigma, chi, alpha, T, m, T, m),
                    -(1 - alpha * alpha) * T * omega / 2.0, 1e-13);
        // Agrees with the unrearranged form of the derivation.
        EXPECT_NEAR(energy_rate(d, 0.3, 1.2, 1.4, 0.7, 2.0, 1.0, 1.0, 2.5),
                    reference_energy_rate(d, 0.3, 1.2, 1.4, 0.7, 2.0, 1.0, 1.0, 2.5), 1e-13);
        // Elastic: energy flows from the hotter to the colder species, and is conserved:
        // n_i R_ij + n_j R_ji = 0.
        const double rij = energy_rate(d, 0.7, 1.1, 1.2, 1.0, 3.0, 1.0, 1.0, 4.0);
        const double rji = energy_rate(d, 0.2, 1.1, 1.2, 1.0, 1.0, 4.0, 3.0, 1.0);
        EXPECT_LT(rij, 0.0);
        EXPECT_NEAR(0.2 * rij + 0.7 * rji, 0.0, 1e-14);
    }
}

struct MonteCarloEstimate {
    double energy_rate, energy_rate_err, frequency, frequency_err;
};

// Direct Monte-Carlo evaluation of the collision integrals: v_i, v_j from Maxwellians, n uniform
// on S^{d-1} (n points from j to i, so the pair approaches iff g.n < 0), weight |g.n| Theta(-g.n),
// collision rule v_i' = v_i - mu_ji (1+alpha) (g.n) n.
MonteCarloEstimate monte_carlo_rates(int d, double n_j, double sigma_ij, double chi_ij,
                                     double alpha, double Ti, double mi, double Tj, double mj,
                                     int samples, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    const double si = std::sqrt(Ti / mi);
    const double sj = std::sqrt(Tj / mj);
    const double mu = mj / (mi + mj);
    double sum_e = 0.0, sum_e2 = 0.0, sum_w = 0.0, sum_w2 = 0.0;
    for (int k = 0; k < samples; ++k) {
        double vi[3] = {0, 0, 0}, vj[3] = {0, 0, 0}, nn[3] = {0, 0, 0};
        double norm2 = 0.0;
        for (int a = 0; a < d; ++a) {
            vi[a] = si * normal(rng);
            vj[a] = sj * normal(rng);
            nn[a] = normal(rng);
            norm2 += nn[a] * nn[a];
        }
        const double inv_norm = 1.0 / std::sqrt(norm2);
        double gn = 0.0;
        for (int a = 0; a < d; ++a) {
            nn[a] *= inv_norm;
            gn += (vi[a] - vj[a]) * nn[a];
        }
        // Antithetic directions: of n and -n exactly one (almost surely) gives an approaching
        // pair, so average f(n) Theta(-g.n) and f(-n) Theta(g.n) instead of wasting half the
        // samples; this is the same estimator of the uniform-n integral with lower variance.
        if (gn > 0.0) {
            for (int a = 0; a < d; ++a) nn[a] = -nn[a];
            gn = -gn;
        }
        const double w = -0.5 * gn;
        double e_before = 0.0, e_after = 0.0;
        for (int a = 0; a < d; ++a) {
            const double v_new = vi[a] - mu * (1.0 + alpha) * gn * nn[a];
            e_before += vi[a] * vi[a];
            e_after += v_new * v_new;
        }
        const double de = 0.5 * mi * (e_after - e_before);
        sum_e += w * de;
        sum_e2 += (w * de) * (w * de);
        sum_w += w;
        sum_w2 += w * w;
    }
    const double dd = static_cast<double>(d);
    const double sphere = 2.0 * std::pow(kPi, 0.5 * dd) / std::tgamma(0.5 * dd);  // |S^{d-1}|
    const double scale = n_j * chi_ij * std::pow(sigma_ij, dd - 1.0) * sphere;
    const double ns = static_cast<double>(samples);
    const double mean_e = sum_e / ns, mean_w = sum_w / ns;
    const double err_e = std::sqrt((sum_e2 / ns - mean_e * mean_e) / ns);
    const double err_w = std::sqrt((sum_w2 / ns - mean_w * mean_w) / ns);
    return {scale * mean_e, scale * err_e, scale * mean_w, scale * err_w};
}

TEST(KineticTheory, EnergyRateAgreesWithMonteCarloCollisionIntegral) {
    // Unequal masses and temperatures, alpha = 0.7; both directions (i light & hot, i heavy &
    // cold) so that both signs of R and both terms of the bracket are exercised.
    // The second case is a net heating in which the two terms of the bracket largely cancel;
    // it needs 4x the samples for the same relative statistical error (~0.25%).
    struct Case {
        double Ti, mi, Tj, mj;
        int samples;
    };
    const Case cases[] = {{2.0, 1.0, 1.0, 2.5, 1'000'000}, {1.0, 2.5, 2.0, 1.0, 4'000'000}};
    const double n_j = 0.3, sigma = 1.2, chi = 1.4, alpha = 0.7;
    unsigned seed = 20240611u;
    for (int d : {2, 3}) {
        for (const Case& c : cases) {
            const MonteCarloEstimate mc = monte_carlo_rates(d, n_j, sigma, chi, alpha, c.Ti, c.mi,
                                                            c.Tj, c.mj, c.samples, seed++);
            const double r = energy_rate(d, n_j, sigma, chi, alpha, c.Ti, c.mi, c.Tj, c.mj);
            const double nu =
                enskog_pair_collision_frequency(d, n_j, sigma, chi, c.Ti, c.mi, c.Tj, c.mj);
            std::printf(
                "  d=%d Ti=%.1f mi=%.1f Tj=%.1f mj=%.1f: R theory %.6f MC %.6f +- %.6f (%.2f%%); "
                "nu theory %.6f MC %.6f +- %.6f\n",
                d, c.Ti, c.mi, c.Tj, c.mj, r, mc.energy_rate, mc.energy_rate_err,
                100.0 * std::abs(mc.energy_rate / r - 1.0), nu, mc.frequency, mc.frequency_err);
            // The statistical error (~0.3%) must be small enough for the 1% test to be meaningful.
            EXPECT_LT(mc.energy_rate_err, 0.0035 * std::abs(r));
            EXPECT_NEAR(mc.energy_rate, r, 0.01 * std::abs(r));
            EXPECT_NEAR(mc.frequency, nu, 0.01 * nu);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Heated binary mixture.

TEST(KineticTheory, HeatedRatioIsOneForIdenticalSpeciesAndElasticEqualMassMixtures) {
    for (int d : {2, 3}) {
        for (NoiseConvention conv :
             {NoiseConvention::EqualVelocityVariance, NoiseConvention::EqualForceVariance}) {
            // Mechanically identical species, different number densities.
            const BinaryMixture same{d, 1.3, 1.3, 0.8, 0.8, 0.2, 0.6, 0.7, 0.7, 0.7, 1.5, 1.5, 1.5};
            EXPECT_EQ(heated_mixture_temperature_ratio(same, conv), 1.0);
            // Elastic, equal masses, different sizes and densities.
            const BinaryMixture elastic{d, 2.0, 2.0, 1.0, 2.5, 0.3, 0.05, 1.0, 1.0, 1.0};
            EXPECT_NEAR(heated_mixture_temperature_ratio(elastic, conv), 1.0, 1e-12);
            // Elastic with unequal masses: the collisions alone equilibrate, still 1.
            const BinaryMixture elastic_m{d, 5.0, 1.0, 1.0, 2.5, 0.3, 0.05, 1.0, 1.0, 1.0};
            EXPECT_NEAR(heated_mixture_temperature_ratio(elastic_m, conv), 1.0, 1e-12);
        }
    }
}

TEST(KineticTheory, HeatedRatioEqualVelocityVarianceHeavierSpeciesIsHotter) {
    for (int d : {2, 3}) {
        const double gamma = heated_mixture_temperature_ratio(
            equal_size_mixture(d, 3.0, 0.85), NoiseConvention::EqualVelocityVariance);
        EXPECT_LT(gamma, 1.0) << "d=" << d;  // gamma = T2/T1 with m1 = 3 m2
        EXPECT_GT(gamma, 0.5) << "d=" << d;
    }
}

// gamma = T2/T1 for an equimolar (n1 = n2), equal-size, dilute (chi = 1) mixture with m2 = 1,
// m1 = mass_ratio and a common alpha, as printed by HeatedAndCoolingRatioTable. With equal sizes
// every R_ij carries the same d-dependent prefactor pi^((d-1)/2) sigma^(d-1) / Gamma(d/2), so in
// this Gaussian approximation the ratios do not depend on d (they do for unequal sizes).
// EqualVelocityVariance: the heavy species is hotter (gamma < 1); EqualForceVariance: the light
// species is hotter (gamma > 1); HCS lies in between and below 1.
struct RatioEntry {
    int d;
    double mass_ratio, alpha;
    double gamma_velocity, gamma_force, gamma_hcs;
};
constexpr RatioEntry kRatioTable[] = {
    // clang-format off
    // d  m1/m2  alpha  EqualVelocityVariance  EqualForceVariance  HCS
    {2,  3.0, 0.85, 0.745877497174699, 1.040465028983339, 0.855384658436894},
    {2,  3.0, 0.50, 0.481550012510104, 1.110278929412099, 0.582756781543598},
    {2, 10.0, 0.85, 0.435120923816180, 1.106173663585210, 0.572259725840425},
    {2, 10.0, 0.50, 0.184829695761064, 1.282703197013382, 0.230286145358150},
    {3,  3.0, 0.85, 0.745877497174699, 1.040465028983339, 0.855384658436894},
    {3,  3.0, 0.50, 0.481550012510104, 1.110278929412099, 0.582756781543598},
    {3, 10.0, 0.85, 0.435120923816180, 1.106173663585210, 0.572259725840425},
    {3, 10.0, 0.50, 0.184829695761064, 1.282703197013382, 0.230286145358150},
    // clang-format on
};

TEST(KineticTheory, HeatedAndCoolingRatioTable) {
    std::printf("  gamma = T2/T1, n1 = n2, sigma1 = sigma2, chi = 1, m2 = 1\n");
    std::printf("  %2s %6s %6s %22s %22s %22s\n", "d", "m1/m2", "alpha", "EqualVelocityVariance",
                "EqualForceVariance", "HCS");
    for (const RatioEntry& e : kRatioTable) {
        const BinaryMixture mix = equal_size_mixture(e.d, e.mass_ratio, e.alpha);
        const double gv =
            heated_mixture_temperature_ratio(mix, NoiseConvention::EqualVelocityVariance);
        const double gf =
            heated_mixture_temperature_ratio(mix, NoiseConvention::EqualForceVariance);
        const double gh = hcs_temperature_ratio(mix);
        std::printf("  %2d %6.1f %6.2f %22.15f %22.15f %22.15f\n", e.d, e.mass_ratio, e.alpha, gv,
                    gf, gh);
        EXPECT_NEAR(gv, e.gamma_velocity, 1e-11 * e.gamma_velocity);
        EXPECT_NEAR(gf, e.gamma_force, 1e-11 * e.gamma_force);
        EXPECT_NEAR(gh, e.gamma_hcs, 1e-11 * e.gamma_hcs);
        EXPECT_LT(gv, 1.0);
        EXPECT_GT(gf, 1.0);
        EXPECT_LT(gh, 1.0);
        // Independent recomputation: both balance equations (heated) and zeta_1 = zeta_2 (HCS)
        // evaluated with the reference energy rates at the returned gamma.
        EXPECT_LT(heated_residual(mix, NoiseConvention::EqualVelocityVariance, gv), 1e-10);
        EXPECT_LT(heated_residual(mix, NoiseConvention::EqualForceVariance, gf), 1e-10);
        EXPECT_LT(hcs_residual(mix, gh), 1e-10);
    }
}

TEST(KineticTheory, TemperatureRatiosSolveBalanceForGenericDenseMixture) {
    // Unequal sizes, densities and restitution coefficients, Enskog contact values.
    for (int d : {2, 3}) {
        const double sigma1 = 1.0, sigma2 = 1.6, n1 = 0.3, n2 = 0.1;
        const double phi =
            unit_ball_volume(d) * (n1 * std::pow(sigma1, d) + n2 * std::pow(sigma2, d));
        const std::vector<double> chi =
            contact_values_mixture(d, phi, {sigma1, sigma2}, {n1 / (n1 + n2), n2 / (n1 + n2)});
        const BinaryMixture mix{d,   0.7,  2.0, sigma1, sigma2, n1,    n2,
                                0.9, 0.75, 0.6, chi[0], chi[1], chi[3]};
        const double gv =
            heated_mixture_temperature_ratio(mix, NoiseConvention::EqualVelocityVariance);
        const double gf =
            heated_mixture_temperature_ratio(mix, NoiseConvention::EqualForceVariance);
        const double gh = hcs_temperature_ratio(mix);
        std::printf("  d=%d phi=%.4f: gamma EVV %.12f EFV %.12f HCS %.12f\n", d, phi, gv, gf, gh);
        EXPECT_LT(heated_residual(mix, NoiseConvention::EqualVelocityVariance, gv), 1e-10);
        EXPECT_LT(heated_residual(mix, NoiseConvention::EqualForceVariance, gf), 1e-10);
        EXPECT_LT(hcs_residual(mix, gh), 1e-10);
    }
}

// ---------------------------------------------------------------------------------------------
// Homogeneous cooling state.

TEST(KineticTheory, HcsRatioIsOneForIdenticalSpeciesAndElasticMixtures) {
    for (int d : {2, 3}) {
        const BinaryMixture same{d, 1.3, 1.3, 0.8, 0.8, 0.2, 0.6, 0.7, 0.7, 0.7, 1.5, 1.5, 1.5};
        EXPECT_EQ(hcs_temperature_ratio(same), 1.0);
        const BinaryMixture elastic{d, 5.0, 1.0, 1.0, 2.5, 0.3, 0.05, 1.0, 1.0, 1.0};
        EXPECT_NEAR(hcs_temperature_ratio(elastic), 1.0, 1e-12);
    }
}

TEST(KineticTheory, HcsRatioHeavierSpeciesIsHotterAndNonequipartitionGrowsWithInelasticity) {
    // Equal sizes and a common alpha: T_heavy > T_light, and the effect grows with 1 - alpha
    // (Garzo & Dufty 1999).
    for (int d : {2, 3}) {
        double previous = 1.0;
        for (double alpha : {0.95, 0.8, 0.6, 0.4}) {
            const double gamma = hcs_temperature_ratio(equal_size_mixture(d, 4.0, alpha));
            EXPECT_LT(gamma, previous) << "d=" << d << " alpha=" << alpha;
            previous = gamma;
        }
    }
}

TEST(KineticTheory, TemperatureRatioIsInverseMassRatioForCompletelyInelasticEquimolarMixture) {
    // Exact limit: with alpha = 0, n1 = n2 and equal sizes, T_i/m_i = T_j/m_j makes every bracket
    // of R_ij equal to -m_i/M, so sum_j R_1j/m_1 = sum_j R_2j/m_2 and, since then also
    // T_2/T_1 = m_2/m_1, zeta_1 = zeta_2: both EqualVelocityVariance and HCS give gamma = m2/m1.
    for (int d : {2, 3}) {
        for (double mass_ratio : {0.2, 3.0, 10.0}) {
            const BinaryMixture mix = equal_size_mixture(d, mass_ratio, 0.0);
            EXPECT_NEAR(
                heated_mixture_temperature_ratio(mix, NoiseConvention::EqualVelocityVariance),
                1.0 / mass_ratio, 1e-12 / mass_ratio);
            EXPECT_NEAR(hcs_temperature_ratio(mix), 1.0 / mass_ratio, 1e-12 / mass_ratio);
        }
    }
}

TEST(KineticTheory, TemperatureRatioSolversRejectInvalidMixtures) {
    BinaryMixture bad = equal_size_mixture(4, 2.0, 0.8);
    EXPECT_THROW(hcs_temperature_ratio(bad), std::invalid_argument);
    bad = equal_size_mixture(2, -1.0, 0.8);
    EXPECT_THROW(heated_mixture_temperature_ratio(bad, NoiseConvention::EqualVelocityVariance),
                 std::invalid_argument);
    bad = equal_size_mixture(3, 2.0, 1.2);
    EXPECT_THROW(hcs_temperature_ratio(bad), std::invalid_argument);
}

}  // namespace
}  // namespace gran::theory
