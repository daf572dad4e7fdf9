#pragma once
// Analytic kinetic-theory predictions that the event-driven simulation is validated against.
//
// Conventions throughout:
//   * Temperatures are in energy units (k_B = 1) and per velocity component: T = m <v_alpha^2>.
//   * d is the spatial dimension, 2 (hard disks) or 3 (hard spheres); anything else throws
//     std::invalid_argument.
//   * sigma is a diameter; sigma_ij = (sigma_i + sigma_j)/2 for additive mixtures.
//   * Velocity distributions are Maxwellians at the (partial) temperatures ("Gaussian
//     approximation"); contact values chi enter as the Enskog factor.
//   * Collision rule for species i hitting j with unit vector n along the line of centres and
//     relative velocity g = v_i - v_j:  v_i' = v_i - mu_ji (1 + alpha_ij) (g.n) n,
//     mu_ji = m_j / (m_i + m_j).
//
// Geometric constants used below (all from Gaussian integrals over the unit sphere S^{d-1}):
//   |S^{d-1}| = 2 pi^(d/2) / Gamma(d/2);
//   B_k = int dn Theta(g^.n) (g^.n)^k = pi^((d-1)/2) Gamma((k+1)/2) / Gamma((k+d)/2);
//   for g ~ N(0, s2 I_d):  <|g|^k> = (2 s2)^(k/2) Gamma((k+d)/2) / Gamma(d/2).
#include <vector>

namespace gran::theory {

// Volume of a d-ball of diameter 1: V_d = pi^(d/2) / (2^d Gamma(d/2 + 1)); pi/4 (2D), pi/6 (3D).
// Packing fraction phi = n V_d sigma^d.
double unit_ball_volume(int d);

// Hard-disk pair correlation at contact, D. Henderson, Mol. Phys. 30, 971 (1975):
//   chi(phi) = (1 - 7 phi / 16) / (1 - phi)^2.
double contact_value_henderson_2d(double phi);

// Hard-sphere pair correlation at contact from the Carnahan-Starling equation of state,
// N. F. Carnahan & K. E. Starling, J. Chem. Phys. 51, 635 (1969):
//   chi(phi) = (1 - phi / 2) / (1 - phi)^3.
double contact_value_carnahan_starling(double phi);

// Monodisperse contact value: d = 2 -> Henderson, d = 3 -> Carnahan-Starling.
double contact_value(int d, double phi);

// Contact values chi_ij of an additive mixture with diameters sigma_i, number fractions x_i
// (normalised internally by sum x) and total packing fraction phi = n V_d <sigma^d>, with
// <sigma^k> = sum_i x_i sigma_i^k and z_ij = sigma_i sigma_j / sigma_ij.
//   3D, Boublik-Mansoori-Carnahan-Starling-Leland: T. Boublik, J. Chem. Phys. 53, 471 (1970);
//   G. A. Mansoori et al., J. Chem. Phys. 54, 1523 (1971):
//     chi_ij = 1/(1-phi) + (3/2) phi/(1-phi)^2 z_ij <sigma^2>/<sigma^3>
//              + (1/2) phi^2/(1-phi)^3 (z_ij <sigma^2>/<sigma^3>)^2.
//   2D, J. T. Jenkins & F. Mancini, J. Appl. Mech. 54, 27 (1987); identical to the d = 2 case of
//   A. Santos, S. B. Yuste & M. Lopez de Haro, Mol. Phys. 96, 1 (1999) with Henderson's chi:
//     chi_ij = 1/(1-phi) + (9/16) phi/(1-phi)^2 z_ij <sigma>/<sigma^2>.
// Both reduce to contact_value(d, phi) when all sizes are equal (z_ij <sigma^{d-1}>/<sigma^d> = 1).
// Returns the row-major ns x ns matrix chi[i * ns + j], ns = sigma.size() = x.size().
std::vector<double> contact_values_mixture(int d, double phi, const std::vector<double>& sigma,
                                           const std::vector<double>& x);
// The same chi_ij one pair at a time (no ns x ns matrix: scenes of 10^4 species), from the
// diameters sigma_i, sigma_j of the pair; the same values bit for bit.
class MixtureContactValues {
  public:
    MixtureContactValues(int d, double phi, const std::vector<double>& sigma,
                         const std::vector<double>& x);
    double operator()(double sigma_i, double sigma_j) const;

  private:
    int d_;
    double phi_;
    double moment_ratio_ = 1;  // <sigma^(d-1)> / <sigma^d>
};

// Equation of state of an inelastic hard-sphere mixture (Barrat & Trizac 2002, Eq. (4), derived in
// their Appendix B from the collisional momentum transfer, Eq. (B8)):
//   P = sum_i n_i T_i + 2^(d-1) V_d sum_ij n_i n_j sigma_ij^d chi_ij (1 + alpha_ij)
//                                        (m_j T_i + m_i T_j) / (2 (m_i + m_j))
// (ordered pairs; V_d the volume of a unit-diameter ball). Monodisperse 2D: P = n T [1 + (1 +
// alpha) phi chi], Eq. (7). Replacing T_i by a component T_{i,a} gives P_aa (the paper's Fig. 4b).
// chi is row-major ns x ns (e.g. contact_values_mixture), alpha likewise.
double enskog_pressure(int d, const std::vector<double>& n, const std::vector<double>& T,
                       const std::vector<double>& m, const std::vector<double>& sigma,
                       const std::vector<double>& alpha, const std::vector<double>& chi);

// Enskog collision frequency per particle of a monodisperse gas at number density n
// (each collision counted once for each of the two partners), Maxwellian at T:
//   omega = n sigma^(d-1) chi B_1 <|g|>  with s2 = 2 T/m
//         = S n sigma^(d-1) chi sqrt(T/m),   S = 2 pi^((d-1)/2) / Gamma(d/2)
// i.e. S = 2 sqrt(pi) (2D), 4 sqrt(pi) (3D); e.g. N. V. Brilliantov & T. Poeschel, Kinetic Theory
// of Granular Gases (OUP 2004), and S. Chapman & T. G. Cowling for d = 3.
double enskog_collision_frequency(int d, double n, double sigma, double chi, double T, double m);

// Frequency with which ONE particle of species i collides with particles of species j (density
// n_j), both Maxwellian (T_i, T_j); g = v_i - v_j is Gaussian with variance s2 = T_i/m_i + T_j/m_j
// per component, so nu_ij = n_j chi_ij sigma_ij^(d-1) B_1 <|g|>:
//   nu_ij = S' n_j chi_ij sigma_ij^(d-1) sqrt(2 (T_i/m_i + T_j/m_j)),
//   S' = pi^((d-1)/2) / Gamma(d/2)  (sqrt(pi) in 2D, 2 pi in 3D).
// With equal species, sum_j nu_ij = enskog_collision_frequency (sqrt(2 * 2T/m) = 2 sqrt(T/m)).
double enskog_pair_collision_frequency(int d, double n_j, double sigma_ij, double chi_ij, double Ti,
                                       double mi, double Tj, double mj);

// Haff's law, P. K. Haff, J. Fluid Mech. 134, 401 (1983), Maxwellian approximation:
// (d/2) dT/dt = R (monodisperse R = -(1-alpha^2) T omega / 2) gives dT/dt = -zeta T with
// zeta = (1 - alpha^2) omega(T) / d and omega ~ sqrt(T), hence
//   T(t) = T0 / (1 + t/t0)^2,   t0 = 2 / zeta(T0) = 2 d / ((1 - alpha^2) omega(T0)).
// haff_time_scale throws unless 0 <= alpha < 1 (alpha = 1: no cooling) and omega0 > 0.
double haff_time_scale(int d, double alpha, double omega0);
double haff_temperature(double T0, double t0, double t);

// Sonine coefficient a2 = <c^4> / <c^4>_Maxwell - 1 of the steady state of a monodisperse gas
// heated by white noise, in the first Sonine approximation (T. P. C. van Noije & M. H. Ernst,
// Granular Matter 1, 57 (1998)):
//   a2 = 16 (1 - alpha)(1 - 2 alpha^2) / (73 + 56 d - 24 d alpha - 105 alpha + 30 (1 - alpha)
//   alpha^2).
// Zero for alpha = 1 and alpha = 1/sqrt(2); 0.0256 for spheres and 0.0356 for disks at alpha = 0.5.
double white_noise_sonine_a2(int d, double alpha);

// Sonine coefficient a2 of the homogeneous cooling state of a monodisperse gas, first Sonine
// approximation (T. P. C. van Noije & M. H. Ernst, Granular Matter 1, 57 (1998)):
//   a2 = 16 (1 - alpha)(1 - 2 alpha^2) / (9 + 24 d - alpha (41 - 8 d) + 30 (1 - alpha) alpha^2).
// Zero for alpha = 1 and 1/sqrt(2); -0.0269 for disks and -0.0146 for spheres at alpha = 0.9. The
// cooling rate per collision per particle is then zeta* = (1 - alpha^2) / d (1 + 3 a2 / 16).
double hcs_sonine_a2(int d, double alpha);

// Mean rate of change of the kinetic energy of ONE particle of species i due to collisions with
// species j (Enskog, both species Maxwellian at T_i, T_j). Derivation: per collision
// Delta E_i = (m_i/2) [a^2 - 2 a v_i.n], a = mu_ji (1+alpha_ij) g.n; given g,
// <v_i | g> = (T_i/m_i)/s2 g; the collision integral then needs B_3 <|g|^3> =
// pi^((d-1)/2) 2^(3/2) s2^(3/2) / Gamma(d/2). With M = m_i + m_j and s2 = T_i/m_i + T_j/m_j:
//   R_ij = n_j chi_ij sigma_ij^(d-1) (pi^((d-1)/2) 2^(3/2) s2^(3/2) / Gamma(d/2)) (m_i/2)
//          mu_ji (1+alpha_ij) [ -2 (T_i - T_j)/(M s2) - mu_ji (1 - alpha_ij) ].
// sum_j R_ij = -(d/2) T_i zeta_i with zeta_i the Gaussian-approximation partial cooling rate of
// V. Garzo & J. W. Dufty, Phys. Rev. E 60, 5706 (1999) (written there with theta_i = m_i v0^2/2T_i,
// where the bracket reads 1 - mu_ji (1+alpha_ij)(1 + theta_i/theta_j)/2). The formula is checked
// against a direct Monte-Carlo evaluation of the collision integral in the unit tests.
// Limits: elastic with T_i = T_j gives 0; monodisperse gives R = -(1-alpha^2) T omega / 2.
double energy_rate(int d, double n_j, double sigma_ij, double chi_ij, double alpha_ij, double Ti,
                   double mi, double Tj, double mj);

// Normalisation of the white-noise thermostat between the two species of a binary mixture.
enum class NoiseConvention {
    EqualVelocityVariance,  // xi_1 = xi_2 (same velocity kicks; e.g. A. Barrat & E. Trizac,
                            // Granular Matter 4, 57 (2002))
    EqualForceVariance      // m_1 xi_1 = m_2 xi_2 (same random force)
};

// Binary mixture: masses, diameters, number densities, restitution coefficients and contact
// values (default chi = 1: the dilute / Boltzmann limit).
struct BinaryMixture {
    int d;
    double m1, m2, sigma1, sigma2, n1, n2;
    double alpha11, alpha12, alpha22;
    double chi11 = 1, chi12 = 1, chi22 = 1;
};

// Steady state of the binary mixture heated by a white-noise thermostat (Fokker-Planck term
// (xi_i^2/2) Laplacian_v f_i, heating per particle d m_i xi_i^2 / 2):
//   sum_j R_ij + d m_i xi_i^2 / 2 = 0,  i = 1, 2   (R_ij from energy_rate, sigma_ij additive).
// EqualVelocityVariance: (sum_j R_1j)/m_1 = (sum_j R_2j)/m_2;
// EqualForceVariance:    m_1 sum_j R_1j = m_2 sum_j R_2j.
// Since every R_ij scales as T^(3/2) at fixed gamma, only gamma = T_2/T_1 is determined. It is
// found by scanning [1e-4, 1e4] on a logarithmic grid for the sign change and refining with
// Brent's method in ln(gamma) to ~1e-13 relative. Throws std::runtime_error if there is no root
// or more than one in that range.
double heated_mixture_temperature_ratio(const BinaryMixture& mix, NoiseConvention convention);

// Homogeneous cooling state of the binary mixture (Garzo & Dufty 1999): both species cool at the
// same rate, zeta_1 = zeta_2 with zeta_i = -2 sum_j R_ij / (d T_i). Returns gamma = T_2/T_1, solved
// as in heated_mixture_temperature_ratio.
double hcs_temperature_ratio(const BinaryMixture& mix);

}  // namespace gran::theory
