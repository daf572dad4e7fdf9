"""The qualitative statements Barrat & Trizac 2002 make about Figs. 1-17, checked on our runs.

Most of what the paper says about its figures is qualitative ("the density is lower near the
walls", "gamma increases from the boundaries to the center"). Each check below quotes the
sentence, states the test applied to our data (the thresholds are ours, not the paper's) and
returns whether it holds with the numbers behind it. figures.py writes them to claims.csv.
"""
import csv

import numpy as np

from analysis import l1_distance, l1_to_gaussian, local_maxima, mono

CHECKS = []
MIDDLE = (0.4, 0.6)  # central window of the profiles (as the `middle` values of gran)
FIG1 = [(a, p) for a in (0.9, 0.8) for p in (0.015, 0.04)]
FIG2_BETAS = (-1, -0.8, -0.5, -0.2)


def check(figure, statement, test):
    """Register a check: `statement` quoted from the paper, `test` what we verify."""
    def register(fn):
        CHECKS.append({"figure": figure, "statement": statement, "test": test, "fn": fn})
        return fn
    return register


def window(profile, lo, hi):
    """Mean of a profile (y/L, value, error) over lo < y/L < hi, with its error."""
    y, v, e = profile
    sel = (y > lo) & (y < hi)
    return float(v[sel].mean()), float(np.sqrt(np.sum(e[sel] ** 2)) / sel.sum())


def wall_and_middle(profile):
    """(value next to the walls (first and last slab), value in the middle window)."""
    y, v, e = profile
    return 0.5 * (v[0] + v[-1]), window(profile, *MIDDLE)[0]


def heterogeneity(run):
    """phi(middle)/phi(wall) of a one-component run."""
    wall, middle = wall_and_middle(run.profile("grain/packing_fraction"))
    return middle / wall


def spread(profile, lo=0.2, hi=0.8):
    """(max - min)/mean of a profile over lo < y/L < hi."""
    y, v, _ = profile
    v = v[(y > lo) & (y < hi)]
    return float((v.max() - v.min()) / v.mean())


def gaussian_cutoff(run, g=1.0):
    """R of P(alpha_1d | g_x) ~ exp(-(alpha_1d g_x)^2/R), fitted for alpha_1d > 1."""
    alpha, p, err = run.conditional(g)
    sel = (alpha > 1) & (p > 0) & (err < p / 4)
    if sel.sum() < 3:
        return float("nan")
    slope = np.polyfit((alpha[sel] * g) ** 2, np.log(p[sel]), 1, w=p[sel] / err[sel])[0]
    return float(-1 / slope)


def increasing(values):
    """Whether a sequence increases strictly."""
    return bool(np.all(np.diff(values) > 0))


def est(value_error, digits=3):
    """A value with its error in parentheses, e.g. 0.656(0.003)."""
    value, error = value_error
    return f"{value:.{digits}f}({error:.{digits}f})"


def fmt(values):
    """Short text of a list of numbers."""
    return ", ".join(f"{v:.3g}" for v in values)


# --- one-component gas ------------------------------------------------------------------------

@check("1, 2", "the density is lower near the walls, where the temperature is higher",
       "phi and T in the wall slabs against the middle window, every Fig. 1-2 run")
def density_low_temperature_high_at_walls(res):
    names = [mono(a, -1, p) for a, p in FIG1] + [mono(0.9, b, 0.015) for b in FIG2_BETAS[1:]]
    phi = [wall_and_middle(res[n].profile("grain/packing_fraction")) for n in names]
    temp = [wall_and_middle(res[n].profile("grain/T")) for n in names]
    holds = all(w < m for w, m in phi) and all(w > m for w, m in temp)
    return holds, (f"phi_wall/phi_middle {fmt([w / m for w, m in phi])}; "
                   f"T_wall/T_middle {fmt([w / m for w, m in temp])}")


@check("1", "As the mean density increases [...] the profiles get more heterogeneous",
       "phi(middle)/phi(wall) larger at phi0 = 0.04 than at 0.015, alpha = 0.9 and 0.8")
def denser_more_heterogeneous(res):
    h = {(a, p): heterogeneity(res[mono(a, -1, p)]) for a, p in FIG1}
    holds = all(h[(a, 0.04)] > h[(a, 0.015)] for a in (0.9, 0.8))
    return holds, "; ".join(f"alpha {a}, phi0 {p}: {v:.3f}" for (a, p), v in h.items())


@check("1", "As the mean density increases or [alpha] decreases, the profiles get more "
       "heterogeneous (the symbol is lost in the extracted text; read as alpha)",
       "phi(middle)/phi(wall) larger at alpha = 0.8 than 0.9, both densities")
def more_inelastic_more_heterogeneous(res):
    h = {(a, p): heterogeneity(res[mono(a, -1, p)]) for a, p in FIG1}
    holds = all(h[(0.8, p)] > h[(0.9, p)] for p in (0.015, 0.04))
    return holds, "; ".join(f"alpha {a}, phi0 {p}: {v:.3f}" for (a, p), v in h.items())


@check("2", "as beta is increased, more energy is transferred to rotational degrees of freedom, "
       "so that the temperature decreases, while the density profiles become slightly more peaked",
       "mean T over the cell decreases and phi(middle)/phi0 increases along beta = -1, -0.8, "
       "-0.5, -0.2")
def rotation_cools_and_peaks(res):
    runs = [res[mono(0.9, b, 0.015)] for b in FIG2_BETAS]
    temps = [float(r.profile("grain/T")[1].mean()) for r in runs]
    peaks = [window(r.density_profile("grain"), *MIDDLE)[0] for r in runs]
    return increasing(peaks) and increasing(temps[::-1]), f"T {fmt(temps)}; peak {fmt(peaks)}"


@check("3", "the temperature is anisotropic [...] with T_y > T > T_x",
       "T_y > T > T_x in every slab (alpha = 0.9, phi0 = 0.04)")
def anisotropic_temperature(res):
    run = res[mono(0.9, -1, 0.04)]
    tx, t, ty = (run.profile(f"grain/{k}")[1] for k in ("T_x", "T", "T_y"))
    return bool(np.all(ty > t) and np.all(t > tx)), f"min (T_y - T_x)/T {np.min((ty - tx) / t):.3f}"


@check("3", "The anisotropy A(y) is larger at the boundaries, [...] decreases due to "
       "inter-particle collisions, and reaches a plateau in the middle of the slab",
       "A(wall) > 2 A(middle), and A over 0.3 < y/L < 0.7 within 0.05 of its mean")
def anisotropy_plateau(res):
    profile = res[mono(0.9, -1, 0.04)].profile("mixture/anisotropy")
    wall, middle = wall_and_middle(profile)
    y, a, _ = profile
    plateau = a[(y > 0.3) & (y < 0.7)]
    holds = wall > 2 * middle and np.all(np.abs(plateau - plateau.mean()) < 0.05)
    return bool(holds), (f"A(wall) {wall:.3f}, A(middle) {middle:.3f}, A over 0.3-0.7 in "
                         f"[{plateau.min():.3f}, {plateau.max():.3f}]")


@check("3", "The plateau value decreases for increasing number of particles or increasing "
       "densities (not shown)", "A(middle) at phi0 = 0.04 below A(middle) at 0.015 (alpha = 0.9)")
def plateau_decreases_with_density(res):
    a = [res[mono(0.9, -1, p)].middle("mixture/anisotropy") for p in (0.015, 0.04)]
    return a[1][0] < a[0][0], f"A(middle) {est(a[0], 4)} (phi0 0.015), {est(a[1], 4)} (0.04)"


@check("4", "With Enskog correction, the corresponding profiles [P_yy with T_y] are remarkably "
       "flat", "(max - min)/mean of P_yy from Eq. (7) with T_y below 5% in 0.05 < y/L < 0.95, "
       "alpha = 0.9, 0.8, 0.7")
def enskog_pyy_flat(res):
    s = [spread(res[mono(a, -1, 0.04)].profile("eos/P_enskog_yy"), 0.05, 0.95)
         for a in (0.9, 0.8, 0.7)]
    return max(s) < 0.05, f"spread {fmt(s)}"


@check("4", "the Enskog correction is necessary for the densities used in Fig. 4",
       "the ideal part rho T_y spreads at least twice as much as the Enskog P_yy over "
       "0.2 < y/L < 0.8")
def enskog_needed(res):
    runs = [res[mono(a, -1, 0.04)] for a in (0.9, 0.8, 0.7)]
    ideal = [spread(r.profile("eos/P_ideal_yy")) for r in runs]
    enskog = [spread(r.profile("eos/P_enskog_yy")) for r in runs]
    holds = all(i > 2 * e for i, e in zip(ideal, enskog))
    return holds, f"ideal {fmt(ideal)}; Enskog {fmt(enskog)}"


@check("4", "In all cases, boundary layers [...] are observed in which the pressure [with the "
       "total T] decreases", "P from Eq. (7) with T lower in the second slab from each wall "
       "than in the middle window, alpha = 0.9, 0.8, 0.7")
def pressure_boundary_layer(res):
    ratios = []
    for a in (0.9, 0.8, 0.7):
        y, p, _ = res[mono(a, -1, 0.04)].profile("eos/P_enskog")
        ratios.append(0.5 * (p[1] + p[-2]) / window((y, p, np.zeros_like(p)), *MIDDLE)[0])
    return all(r < 1 for r in ratios), f"P(near wall)/P(middle) {fmt(ratios)}"


@check("6", "A smooth distribution is obtained in the vicinity of a thermal wall, while the "
       "incoming and out-coming particles yield two separated peaks for vibrating walls",
       "significant maxima of P(c_y) in the slab 0 < y/L < 0.05: two (sawtooth), one (thermal)")
def wall_peaks(res):
    peaks = {w: local_maxima(*res[mono(0.9, 0, 0.04, w)].slab_pdf(0.025, "y"))
             for w in ("sawtooth", "thermal")}
    holds = len(peaks["sawtooth"]) == 2 and len(peaks["thermal"]) == 1
    return holds, (f"sawtooth peaks at c_y = {fmt(peaks['sawtooth'])}; "
                   f"thermal at c_y = {fmt(peaks['thermal'])}")


def close_pdfs(a, b):
    """Whether two distributions are closer to each other than half their distance to the
    Gaussian (L1 distances over |c| < 4), with the numbers."""
    l1, ga, gb = l1_distance(a, b), l1_to_gaussian(a), l1_to_gaussian(b)
    return l1 < 0.5 * min(ga, gb), f"L1 distance {l1:.4f}; to the Gaussian {ga:.4f}, {gb:.4f}"


def kurtosis(res, name, centre=0.5, species=None):
    """Kurtosis of P(c_x) in a slab."""
    return res[name].slab_scalar(centre, "x", "kurtosis", species)


@check("7", "Fig. 7 shows clearly non-Gaussian features [...] with in particular overpopulated "
       "both small-velocity and high-velocity regions",
       "middle-slab kurtosis of c_x above 3 and P(c_x = 0) above 1/sqrt(2 pi), Fig. 7 runs")
def non_gaussian(res):
    names = [mono(0.9, 0, 0.015), mono(0.8, 0, 0.015), mono(0.9, 0, 0.015, "thermal")]
    kurt = [kurtosis(res, n) for n in names]
    p0 = [float(np.interp(0.0, *res[n].slab_pdf(0.5, "x")[:2])) for n in names]
    holds = all(k > 3 for k in kurt) and all(p > 1 / np.sqrt(2 * np.pi) for p in p0)
    return holds, f"kurtosis {fmt(kurt)}; P(0) {fmt(p0)} (Gaussian 0.399)"


@check("7", "P(c_x) broadens if the inelasticity increases (i.e. if alpha decreases), if beta "
       "increases, or if phi0 [...] increase",
       "middle-slab kurtosis: alpha 0.8 > 0.9 (beta 0); beta 0 > -1; phi0 0.04 > 0.015 (alpha 0.9)")
def broadening(res):
    base = kurtosis(res, mono(0.9, 0, 0.015))
    other = {"alpha 0.8": kurtosis(res, mono(0.8, 0, 0.015)),
             "beta -1 (should be below)": kurtosis(res, mono(0.9, -1, 0.015)),
             "phi0 0.04": kurtosis(res, mono(0.9, 0, 0.04))}
    values = list(other.values())
    holds = values[0] > base and values[1] < base and values[2] > base
    return holds, f"alpha 0.9, beta 0, phi0 0.015: {base:.3f}; " + "; ".join(
        f"{k}: {v:.3f}" for k, v in other.items())


@check("7", "thermal walls lead to slightly broader velocity distributions than vibrating walls",
       "middle-slab kurtosis of c_x, thermal above sawtooth (alpha 0.9, beta 0, phi0 0.015 and "
       "0.04)")
def thermal_broader(res):
    k = {p: (kurtosis(res, mono(0.9, 0, p, "thermal")), kurtosis(res, mono(0.9, 0, p)))
         for p in (0.015, 0.04)}
    return all(t > s for t, s in k.values()), "; ".join(
        f"phi0 {p}: thermal {t:.3f}, sawtooth {s:.3f}" for p, (t, s) in k.items())


@check("7", "the rescaled horizontal velocity distribution P(c_x) is remarkably independent of "
       "the distance from the walls (outside the boundary layers)",
       "L1 distance (integral of |P_a - P_b| over |c_x| < 4) between y/L = 0.25 and 0.5 below "
       "half the distance of either to the Gaussian (vibrating, alpha 0.9, beta 0, phi0 0.015)")
def height_independent(res):
    name = mono(0.9, 0, 0.015)
    return close_pdfs(res[name].slab_pdf(0.25, "x"), res[name].slab_pdf(0.5, "x"))


def angular(res, name):
    """Whole-cell kurtosis of the angular velocities of a rough run, with its error."""
    return res[name].angular_kurtosis()


@check("7(b)", "The angular velocity distributions, also displayed in Fig. 7, share a similar "
       "non-Gaussian character", "whole-cell kurtosis of c_w = w/sqrt(T_rot/I) above 3 by more "
       "than 5 errors and above the kurtosis the T_rot(y) profile alone gives (Gaussian in every "
       "slab), and P(c_w = 0) above 1/sqrt(2 pi), Fig. 7 runs")
def angular_non_gaussian(res):
    names = [mono(0.9, 0, 0.015), mono(0.8, 0, 0.015), mono(0.9, 0, 0.015, "thermal")]
    kurt = [angular(res, n) for n in names]
    mixing = [res[n].mixing_kurtosis() for n in names]
    p0 = [float(np.interp(0.0, *res[n].angular_pdf()[0][:2])) for n in names]
    holds = (all(k - 3 > 5 * e for k, e in kurt) and all(k > m for (k, _), m in zip(kurt, mixing))
             and all(p > 1 / np.sqrt(2 * np.pi) for p in p0))
    cx = [kurtosis(res, n) for n in names]
    return holds, (f"kurtosis {', '.join(est(k) for k in kurt)}; from the T_rot profile alone "
                   f"{fmt(mixing)}; P(0) {fmt(p0)} (Gaussian 0.399); middle-slab kurtosis of "
                   f"c_x (panel a) {fmt(cx)}")


@check("7(b)", "[the angular velocity distributions share] the same dependence with the "
       "parameters [as P(c_x): broader if alpha decreases, if beta increases, if phi0 increases; "
       "thermal walls slightly broader]",
       "whole-cell kurtosis of c_w: alpha 0.8 > 0.9 (beta 0); beta -0.8 < -0.5 < -0.2 < 0; "
       "phi0 0.04 > 0.015; thermal > sawtooth at phi0 0.015 and 0.04 (alpha 0.9)")
def angular_dependence(res):
    base = angular(res, mono(0.9, 0, 0.015))[0]
    alpha = angular(res, mono(0.8, 0, 0.015))[0]
    betas = [angular(res, mono(0.9, b, 0.015))[0] for b in (-0.8, -0.5, -0.2)] + [base]
    phi = angular(res, mono(0.9, 0, 0.04))[0]
    thermal = {p: (angular(res, mono(0.9, 0, p, "thermal"))[0], angular(res, mono(0.9, 0, p))[0])
               for p in (0.015, 0.04)}
    holds = (alpha > base and increasing(betas) and phi > base
             and all(t > v for t, v in thermal.values()))
    return holds, (f"alpha 0.9: {base:.3f}, 0.8: {alpha:.3f}; beta -0.8, -0.5, -0.2, 0: "
                   f"{fmt(betas)}; phi0 0.04: {phi:.3f}; " + "; ".join(
                       f"phi0 {p}: thermal {t:.3f}, sawtooth {v:.3f}"
                       for p, (t, v) in thermal.items()))


@check("9", "the cut-off R increases [i.e. leads to broader P(alpha_1d|g_x)] if alpha decreases, "
       "and if beta or phi0 increase",
       "R of exp(-(alpha_1d g_x)^2/R) at g_x = 1: alpha 0.8 > 0.9; beta 0 > -1; phi0 0.04 > 0.015")
def cutoff_trends(res):
    base = gaussian_cutoff(res[mono(0.9, 0, 0.015)])
    alpha = gaussian_cutoff(res[mono(0.8, 0, 0.015)])
    beta = gaussian_cutoff(res[mono(0.9, -1, 0.015)])
    phi = gaussian_cutoff(res[mono(0.9, 0, 0.04)])
    holds = alpha > base and beta < base and phi > base
    return holds, (f"R = {base:.3f} (alpha 0.9, beta 0, phi0 0.015); alpha 0.8: {alpha:.3f}; "
                   f"beta -1: {beta:.3f}; phi0 0.04: {phi:.3f}")


# --- binary mixture ---------------------------------------------------------------------------

@check("13", "generically gamma = T_2/T_1 is smaller than 1 [...] gamma increases from the "
       "boundaries to the center of the system",
       "gamma(middle) < 1 and gamma(wall) < gamma(middle), m1 = 3 m2 and 5 m2")
def gamma_below_one_rising(res):
    pairs = {m: wall_and_middle(res[f"tableI_m{m}_beta0"].gamma_profile()) for m in (3, 5)}
    holds = all(mid < 1 and wall < mid for wall, mid in pairs.values())
    return holds, "; ".join(f"m1 = {m} m2: wall {w:.3f}, middle {c:.3f}"
                            for m, (w, c) in pairs.items())


@check("13", "It decreases if the mass ratio increases (Figs. 13)",
       "gamma(middle) at m1 = 5 m2 below m1 = 3 m2")
def gamma_mass_ratio(res):
    g3, g5 = (res[f"tableI_m{m}_beta0"].middle_gamma() for m in (3, 5))
    return g5[0] < g3[0], f"m1 = 3 m2: {est(g3)}; m1 = 5 m2: {est(g5)}"


@check("13, 14", "The more massive particles (labeled 1), which display a more heterogeneous "
       "profile and are denser in the middle of the cell",
       "rho_1/rho_1,0 above rho_2/rho_2,0 in the middle window (Figs. 13-14 runs)")
def heavy_denser_in_middle(res):
    names = ["tableI_m3_beta0", "tableI_m5_beta0", "tableII_987_beta0", "tableII_789_beta0"]
    mids = [(window(res[n].density_profile("heavy"), *MIDDLE)[0],
             window(res[n].density_profile("light"), *MIDDLE)[0]) for n in names]
    return all(h > l for h, l in mids), "; ".join(f"{n}: {h:.3f} vs {l:.3f}"
                                                  for n, (h, l) in zip(names, mids))


@check("14", "the value of gamma, at given mass ratio, is smaller for inelasticities of "
       "alpha_ij = 0.9;0.8;0.7 than with reverse inelasticities", "gamma(middle), beta = 0")
def gamma_orderings(res):
    g987, g789 = (res[f"tableII_{o}_beta0"].middle_gamma() for o in ("987", "789"))
    return g987[0] < g789[0], f"0.9;0.8;0.7: {g987[0]:.3f}; 0.7;0.8;0.9: {g789[0]:.3f}"


@check("15", "displays only a very weak [...] sensitivity on the global density (Fig. 15)",
       "|gamma(middle, phi0 0.04) - gamma(middle, phi0 0.015)| below 0.05")
def gamma_density(res):
    a, b = (res[n].middle_gamma() for n in ("tableII_987_beta0", "fig15_987_phi0.04"))
    return abs(a[0] - b[0]) < 0.05, f"phi0 0.015: {est(a)}; 0.04: {est(b)}"


@check("15", "we obtain, as in experiments, gamma_x > gamma > gamma_y, with also different "
       "shapes: gamma_x decreases from the walls to the center while gamma and gamma_y increase",
       "middle values ordered; wall slabs against the middle window (phi0 0.015 and 0.04)")
def gamma_components(res):
    out, holds = [], True
    for name in ("tableII_987_beta0", "fig15_987_phi0.04"):
        run = res[name]
        (xw, xm), (gw, gm), (yw, ym) = (wall_and_middle(run.gamma_profile(c))
                                        for c in ("x", "", "y"))
        holds &= xm > gm > ym and xw > xm and gw < gm and yw < ym
        out.append(f"{name}: gamma_x {xw:.3f}->{xm:.3f}, gamma {gw:.3f}->{gm:.3f}, "
                   f"gamma_y {yw:.3f}->{ym:.3f} (wall->middle)")
    return bool(holds), "; ".join(out)


def gamma_vs_fraction(res, order):
    """gamma(middle) along N1/N2 = 1/8 ... 8 for one ordering of the restitutions."""
    runs = [f"fig16_{order}_N1N2_{r}" for r in ("1to8", "1to4")] + [f"tableII_{order}_beta0"] + [
        f"fig16_{order}_N1N2_{r}" for r in ("4to1", "8to1")]
    return [res[n].middle_gamma()[0] for n in runs]


@check("16", "an increase of the relative fraction x1 of heavy particles leads to an increase of "
       "gamma when the heavy particles are the more elastic",
       "gamma(middle) increases along N1/N2 = 1/8, 1/4, 1, 4, 8 for alpha_ij = 0.9;0.8;0.7")
def fraction_heavy_elastic(res):
    g = gamma_vs_fraction(res, "987")
    return increasing(g), f"gamma {fmt(g)}"


@check("16", "an increase of x1 leads a relatively weak decrease of gamma when the heavier "
       "particles are the less elastic",
       "gamma(N1/N2 = 8) < gamma(N1/N2 = 1/8) for 0.7;0.8;0.9, by less than the 0.9;0.8;0.7 rise")
def fraction_heavy_inelastic(res):
    g, other = gamma_vs_fraction(res, "789"), gamma_vs_fraction(res, "987")
    holds = g[-1] < g[0] and abs(g[-1] - g[0]) < abs(other[-1] - other[0])
    return holds, f"gamma {fmt(g)}"


@check("17", "the rescaled velocity distributions P1(c_x) and P2(c_x) are very close (even if not "
       "equal) for both types of particles; horizontal distributions show strong non-Gaussian "
       "features", "L1 distance between P1 and P2 below half the distance of either to the "
       "Gaussian, both kurtoses above 3 (middle slab)")
def species_pdfs_close(res):
    run = res["tableII_987_beta0"]
    holds, evidence = close_pdfs(*(run.slab_pdf(0.5, "x", s) for s in ("heavy", "light")))
    k = [run.slab_scalar(0.5, "x", "kurtosis", s) for s in ("heavy", "light")]
    return holds and min(k) > 3, f"{evidence}; kurtosis {fmt(k)}"


def check_all(res):
    """Run every check: list of dicts (figure, statement, test, holds, evidence)."""
    out = []
    for c in CHECKS:
        holds, evidence = c["fn"](res)
        out.append({"figure": c["figure"], "statement": c["statement"], "test": c["test"],
                    "holds": bool(holds), "evidence": evidence})
    return out


def write_csv(checked, path):
    """Write the checked statements to a CSV file."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["figure", "statement", "test", "holds", "evidence"])
        w.writeheader()
        w.writerows(checked)
