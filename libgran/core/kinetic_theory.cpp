#include "libgran/core/kinetic_theory.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace gran::theory {

namespace {

void check_dimension(int d) {
    if (d != 2 && d != 3) {
        throw std::invalid_argument("gran::theory: dimension must be 2 or 3, got " +
                                    std::to_string(d));
    }
}

void check_packing_fraction(double phi) {
    if (!(phi >= 0.0 && phi < 1.0)) {
        throw std::invalid_argument("gran::theory: packing fraction must lie in [0, 1), got " +
                                    std::to_string(phi));
    }
}

void check_positive(double value, const char* name) {
    if (!(value > 0.0)) {
        throw std::invalid_argument(std::string("gran::theory: ") + name +
                                    " must be positive, got " + std::to_string(value));
    }
}

void check_restitution(double alpha) {
    if (!(alpha >= 0.0 && alpha <= 1.0)) {
        throw std::invalid_argument(
            "gran::theory: restitution coefficient must lie in [0, 1], got " +
            std::to_string(alpha));
    }
}

// pi^((d-1)/2) / Gamma(d/2): 1 (2D), 2 (3D). B_1 <|g|> = this * sqrt(2 s2) and
// B_3 <|g|^3> = this * 2^(3/2) s2^(3/2).
double half_surface_factor_of(int d) {
    const double dd = static_cast<double>(d);
    return std::pow(std::numbers::pi, 0.5 * (dd - 1.0)) / std::tgamma(0.5 * dd);
}
// Computed once per dimension: the pair sums over the species of a scene call it S^2 times
// (10^8 for 10^4 species), where pow and tgamma took most of `gran check`'s time.
double half_surface_factor(int d) {
    static const double f2 = half_surface_factor_of(2), f3 = half_surface_factor_of(3);
    return d == 2 ? f2 : d == 3 ? f3 : half_surface_factor_of(d);
}

// Sum over j of R_ij for species i of a binary mixture at temperatures T1, T2.
double total_energy_rate(const BinaryMixture& mix, int i, double T1, double T2) {
    const double s12 = 0.5 * (mix.sigma1 + mix.sigma2);
    if (i == 1) {
        return energy_rate(mix.d, mix.n1, mix.sigma1, mix.chi11, mix.alpha11, T1, mix.m1, T1,
                           mix.m1) +
               energy_rate(mix.d, mix.n2, s12, mix.chi12, mix.alpha12, T1, mix.m1, T2, mix.m2);
    }
    return energy_rate(mix.d, mix.n1, s12, mix.chi12, mix.alpha12, T2, mix.m2, T1, mix.m1) +
           energy_rate(mix.d, mix.n2, mix.sigma2, mix.chi22, mix.alpha22, T2, mix.m2, T2, mix.m2);
}

void check_mixture(const BinaryMixture& mix) {
    check_dimension(mix.d);
    check_positive(mix.m1, "m1");
    check_positive(mix.m2, "m2");
    check_positive(mix.sigma1, "sigma1");
    check_positive(mix.sigma2, "sigma2");
    check_positive(mix.n1, "n1");
    check_positive(mix.n2, "n2");
    check_positive(mix.chi11, "chi11");
    check_positive(mix.chi12, "chi12");
    check_positive(mix.chi22, "chi22");
    check_restitution(mix.alpha11);
    check_restitution(mix.alpha12);
    check_restitution(mix.alpha22);
}

// Brent's method (R. P. Brent, Algorithms for Minimization without Derivatives, 1973; the
// zbrent variant) for a root of f in [a, b] with f(a) f(b) < 0, to absolute tolerance tol in x.
double brent_root(const std::function<double(double)>& f, double a, double b, double fa, double fb,
                  double tol) {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    double c = b;
    double fc = fb;
    double step = b - a;
    double prev_step = step;
    for (int iter = 0; iter < 500; ++iter) {
        if ((fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0)) {
            c = a;
            fc = fa;
            step = b - a;
            prev_step = step;
        }
        if (std::abs(fc) < std::abs(fb)) {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        const double tol1 = 2.0 * eps * std::abs(b) + 0.5 * tol;
        const double xm = 0.5 * (c - b);
        if (std::abs(xm) <= tol1 || fb == 0.0) return b;
        if (std::abs(prev_step) >= tol1 && std::abs(fa) > std::abs(fb)) {
            // Inverse quadratic interpolation (secant if only two distinct points).
            const double s = fb / fa;
            double p = 0.0;
            double q = 0.0;
            if (a == c) {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                const double qq = fa / fc;
                const double r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if (p > 0.0) q = -q;
            p = std::abs(p);
            const double min1 = 3.0 * xm * q - std::abs(tol1 * q);
            const double min2 = std::abs(prev_step * q);
            if (2.0 * p < std::min(min1, min2)) {
                prev_step = step;
                step = p / q;
            } else {
                step = xm;
                prev_step = step;
            }
        } else {
            step = xm;
            prev_step = step;
        }
        a = b;
        fa = fb;
        b += (std::abs(step) > tol1) ? step : std::copysign(tol1, xm);
        fb = f(b);
    }
    throw std::runtime_error("gran::theory: Brent root finder did not converge");
}

// The unique root gamma in [1e-4, 1e4] of residual(gamma): log-grid scan for the sign change,
// then Brent in x = ln(gamma).
double solve_temperature_ratio(const std::function<double(double)>& residual) {
    const std::function<double(double)> f = [&](double x) { return residual(std::exp(x)); };
    // gamma = 1 exactly is the answer for mechanically equivalent species; test it directly so
    // that such cases return exactly 1.
    if (residual(1.0) == 0.0) return 1.0;

    constexpr int n_grid = 160;  // spacing 0.115 in ln(gamma)
    const double x_lo = std::log(1e-4);
    const double x_hi = std::log(1e4);
    double bracket_lo = 0.0;
    double bracket_hi = 0.0;
    double f_lo = 0.0;
    double f_hi = 0.0;
    int n_roots = 0;
    double x_prev = x_lo;
    double f_prev = f(x_prev);
    if (f_prev == 0.0) {
        ++n_roots;
        bracket_lo = bracket_hi = x_prev;
    }
    for (int k = 1; k <= n_grid; ++k) {
        const double x = x_lo + (x_hi - x_lo) * static_cast<double>(k) / n_grid;
        const double fx = f(x);
        if (!std::isfinite(fx)) {
            throw std::runtime_error("gran::theory: non-finite temperature-ratio residual");
        }
        if (fx == 0.0) {
            ++n_roots;
            bracket_lo = bracket_hi = x;
        } else if ((f_prev < 0.0 && fx > 0.0) || (f_prev > 0.0 && fx < 0.0)) {
            ++n_roots;
            bracket_lo = x_prev;
            bracket_hi = x;
            f_lo = f_prev;
            f_hi = fx;
        }
        x_prev = x;
        f_prev = fx;
    }
    if (n_roots == 0) {
        throw std::runtime_error("gran::theory: no temperature ratio in [1e-4, 1e4]");
    }
    if (n_roots > 1) {
        throw std::runtime_error("gran::theory: several temperature ratios in [1e-4, 1e4]");
    }
    if (bracket_lo == bracket_hi) return std::exp(bracket_lo);
    return std::exp(brent_root(f, bracket_lo, bracket_hi, f_lo, f_hi, 1e-14));
}

}  // namespace

double unit_ball_volume(int d) {
    check_dimension(d);
    const double dd = static_cast<double>(d);
    return std::pow(std::numbers::pi, 0.5 * dd) / (std::pow(2.0, dd) * std::tgamma(0.5 * dd + 1.0));
}

double contact_value_henderson_2d(double phi) {
    check_packing_fraction(phi);
    const double one_minus = 1.0 - phi;
    return (1.0 - 7.0 * phi / 16.0) / (one_minus * one_minus);
}

double contact_value_carnahan_starling(double phi) {
    check_packing_fraction(phi);
    const double one_minus = 1.0 - phi;
    return (1.0 - 0.5 * phi) / (one_minus * one_minus * one_minus);
}

double contact_value(int d, double phi) {
    check_dimension(d);
    return d == 2 ? contact_value_henderson_2d(phi) : contact_value_carnahan_starling(phi);
}

MixtureContactValues::MixtureContactValues(int d, double phi, const std::vector<double>& sigma,
                                           const std::vector<double>& x)
    : d_(d), phi_(phi) {
    check_dimension(d);
    check_packing_fraction(phi);
    if (sigma.size() != x.size() || sigma.empty()) {
        throw std::invalid_argument(
            "gran::theory: contact_values_mixture needs equally many (>0) sizes and fractions");
    }
    double x_sum = 0.0;
    double moment_dm1 = 0.0;  // sum x_i sigma_i^(d-1)
    double moment_d = 0.0;    // sum x_i sigma_i^d
    for (std::size_t i = 0; i < sigma.size(); ++i) {
        check_positive(sigma[i], "sigma");
        if (!(x[i] >= 0.0)) {
            throw std::invalid_argument("gran::theory: number fractions must be non-negative");
        }
        x_sum += x[i];
        const double s_dm1 = d == 2 ? sigma[i] : sigma[i] * sigma[i];
        moment_dm1 += x[i] * s_dm1;
        moment_d += x[i] * s_dm1 * sigma[i];
    }
    if (!(x_sum > 0.0)) {
        throw std::invalid_argument("gran::theory: number fractions sum to zero");
    }
    // The normalisation of x cancels in the ratio of moments.
    moment_ratio_ = moment_dm1 / moment_d;
}

double MixtureContactValues::operator()(double sigma_i, double sigma_j) const {
    const double phi = phi_;
    const double one_minus = 1.0 - phi;
    const double sigma_ij = 0.5 * (sigma_i + sigma_j);
    const double z = sigma_i * sigma_j / sigma_ij * moment_ratio_;
    if (d_ == 2) return 1.0 / one_minus + 9.0 / 16.0 * phi / (one_minus * one_minus) * z;
    return 1.0 / one_minus + 1.5 * phi / (one_minus * one_minus) * z +
           0.5 * phi * phi / (one_minus * one_minus * one_minus) * z * z;
}

std::vector<double> contact_values_mixture(int d, double phi, const std::vector<double>& sigma,
                                           const std::vector<double>& x) {
    const MixtureContactValues chi_of(d, phi, sigma, x);
    const std::size_t ns = sigma.size();
    std::vector<double> chi(ns * ns);
    for (std::size_t i = 0; i < ns; ++i) {
        for (std::size_t j = 0; j < ns; ++j) chi[i * ns + j] = chi_of(sigma[i], sigma[j]);
    }
    return chi;
}

double enskog_collision_frequency(int d, double n, double sigma, double chi, double T, double m) {
    check_dimension(d);
    check_positive(m, "mass");
    // S = 2 pi^((d-1)/2) / Gamma(d/2).
    return 2.0 * half_surface_factor(d) * n * std::pow(sigma, static_cast<double>(d - 1)) * chi *
           std::sqrt(T / m);
}

double enskog_pair_collision_frequency(int d, double n_j, double sigma_ij, double chi_ij, double Ti,
                                       double mi, double Tj, double mj) {
    check_dimension(d);
    check_positive(mi, "mass");
    check_positive(mj, "mass");
    const double s2 = Ti / mi + Tj / mj;
    // sigma^(d-1): in 2D sigma itself (pow(x, 1) is x; the pair sums over 10^4 species call this
    // 10^8 times).
    const double contact = d == 2 ? sigma_ij : std::pow(sigma_ij, static_cast<double>(d - 1));
    return half_surface_factor(d) * n_j * chi_ij * contact * std::sqrt(2.0 * s2);
}

double haff_time_scale(int d, double alpha, double omega0) {
    check_dimension(d);
    if (!(alpha >= 0.0 && alpha < 1.0)) {
        throw std::invalid_argument("gran::theory: Haff's law needs 0 <= alpha < 1");
    }
    check_positive(omega0, "omega0");
    return 2.0 * static_cast<double>(d) / ((1.0 - alpha * alpha) * omega0);
}

double white_noise_sonine_a2(int d, double alpha) {
    check_restitution(alpha);
    const double dd = d;
    return 16 * (1 - alpha) * (1 - 2 * alpha * alpha) /
           (73 + 56 * dd - 24 * dd * alpha - 105 * alpha + 30 * (1 - alpha) * alpha * alpha);
}

double hcs_sonine_a2(int d, double alpha) {
    check_restitution(alpha);
    const double dd = d;
    return 16 * (1 - alpha) * (1 - 2 * alpha * alpha) /
           (9 + 24 * dd - alpha * (41 - 8 * dd) + 30 * (1 - alpha) * alpha * alpha);
}

double haff_temperature(double T0, double t0, double t) {
    check_positive(t0, "t0");
    const double s = 1.0 + t / t0;
    return T0 / (s * s);
}

double energy_rate(int d, double n_j, double sigma_ij, double chi_ij, double alpha_ij, double Ti,
                   double mi, double Tj, double mj) {
    check_dimension(d);
    check_positive(mi, "mass");
    check_positive(mj, "mass");
    const double M = mi + mj;
    const double mu_ji = mj / M;
    const double s2 = Ti / mi + Tj / mj;
    const double prefactor = n_j * chi_ij * std::pow(sigma_ij, static_cast<double>(d - 1)) *
                             half_surface_factor(d) * 2.0 * std::numbers::sqrt2 * s2 *
                             std::sqrt(s2);
    const double bracket = -2.0 * (Ti - Tj) / (M * s2) - mu_ji * (1.0 - alpha_ij);
    return prefactor * 0.5 * mi * mu_ji * (1.0 + alpha_ij) * bracket;
}

double heated_mixture_temperature_ratio(const BinaryMixture& mix, NoiseConvention convention) {
    check_mixture(mix);
    // Weights w_i such that the steady state is w_1 sum_j R_1j = w_2 sum_j R_2j.
    const double w1 = convention == NoiseConvention::EqualVelocityVariance ? 1.0 / mix.m1 : mix.m1;
    const double w2 = convention == NoiseConvention::EqualVelocityVariance ? 1.0 / mix.m2 : mix.m2;
    // T_1 = 1, T_2 = gamma; dividing by (1 + gamma)^(3/2) keeps the residual O(1) on the whole
    // bracket without moving its root.
    return solve_temperature_ratio([&](double gamma) {
        const double r1 = total_energy_rate(mix, 1, 1.0, gamma);
        const double r2 = total_energy_rate(mix, 2, 1.0, gamma);
        return (w1 * r1 - w2 * r2) / std::pow(1.0 + gamma, 1.5);
    });
}

double hcs_temperature_ratio(const BinaryMixture& mix) {
    check_mixture(mix);
    // zeta_1 = zeta_2  <=>  sum_j R_1j / T_1 = sum_j R_2j / T_2 with T_1 = 1, T_2 = gamma.
    return solve_temperature_ratio([&](double gamma) {
        const double r1 = total_energy_rate(mix, 1, 1.0, gamma);
        const double r2 = total_energy_rate(mix, 2, 1.0, gamma);
        return (r1 - r2 / gamma) / std::sqrt(1.0 + gamma);
    });
}

double enskog_pressure(int d, const std::vector<double>& n, const std::vector<double>& T,
                       const std::vector<double>& m, const std::vector<double>& sigma,
                       const std::vector<double>& alpha, const std::vector<double>& chi) {
    const std::size_t ns = n.size();
    double p = 0;
    for (std::size_t i = 0; i < ns; ++i) p += n[i] * T[i];
    const double b = std::pow(2.0, d - 1) * unit_ball_volume(d);
    for (std::size_t i = 0; i < ns; ++i) {
        for (std::size_t j = 0; j < ns; ++j) {
            const double sij = 0.5 * (sigma[i] + sigma[j]);
            p += b * n[i] * n[j] * std::pow(sij, d) * chi[i * ns + j] * (1.0 + alpha[i * ns + j]) *
                 (m[j] * T[i] + m[i] * T[j]) / (2.0 * (m[i] + m[j]));
        }
    }
    return p;
}

}  // namespace gran::theory
