"""Reading the Barrat & Trizac 2002 study results and the fits the figures and checks share.

A `Results` directory holds one gran result file per study point (`<name>.h5`); `Run` gives the
profiles, slab velocity distributions and effective-restitution histograms of one of them (read
through gran.results), every curve as (x, value, error) arrays with x the bin centres.
"""
from pathlib import Path

import numpy as np

from gran import results
from gran.fits import power_law

PROFILES = "observables/profiles"
SLABS = "observables/slab_velocity_pdf"
RESTITUTION = "observables/restitution_statistics"
MIN_FIT_POINTS = 4  # fewer usable bins (short runs): the fits return NaN


def mono(alpha, beta, phi, wall="sawtooth"):
    """Name of a one-component run of monodisperse.yaml (wall: 'sawtooth' or 'thermal')."""
    prefix = "mono_thermal" if wall == "thermal" else "mono"
    return f"{prefix}_a{alpha}_beta{beta}_phi{phi}"


class Run:
    """One gran result file of these studies."""

    def __init__(self, path):
        self.path = Path(path)
        self.result = results.Run.open(self.path)
        self.scene = self.result.scene

    @property
    def species(self):
        """Species names in scene order (the first is the reference of the ratios)."""
        return self.result.species

    @property
    def height(self):
        """Box length along y (the direction of the profiles)."""
        return float(self.scene["box"]["lengths"][1])

    def profile(self, key):
        """Profile `key` (e.g. 'grain/T', 'ratios/light_over_heavy/gamma'): (y/L, value, error)."""
        y, value, error = self.result.profile(f"{PROFILES}/{key}")
        return y / self.height, value, error

    def density_profile(self, species):
        """Number density of one species over its mean across the cell: (y/L, value, error)."""
        y, n, e = self.profile(f"{species}/number_density")
        return y, n / n.mean(), e / n.mean()

    def gamma_profile(self, component=""):
        """gamma(y) = T_2/T_1 (second species over the first), or gamma_x, gamma_y: (y/L, v, e)."""
        heavy, light = self.species
        suffix = f"_{component}" if component else ""
        return self.profile(f"ratios/{light}_over_{heavy}/gamma{suffix}")

    def middle(self, key):
        """Value of a profile over the central window, with its error."""
        return tuple(self.result.estimate(f"{PROFILES}/middle/{key}"))

    def middle_gamma(self, component=""):
        """gamma (or gamma_x, gamma_y) in the middle of the cell, with its error."""
        heavy, light = self.species
        suffix = f"_{component}" if component else ""
        return self.middle(f"ratios/{light}_over_{heavy}/gamma{suffix}")

    def slab(self, centre):
        """Path of the slab velocity distribution centred at `centre` (fraction of L)."""
        for g in self.result.root[SLABS].values():
            if abs(g.attrs["centre"] - centre) < 1e-9:
                return g.name
        raise KeyError(f"{self.path.name}: no slab centred at {centre}")

    def slab_pdf(self, centre, component, species=None, kind="scaled"):
        """Velocity distribution in a slab, rescaled by the slab temperature: (c, P, error)."""
        path = f"{self.slab(centre)}/{species or self.species[0]}/{component}"
        return self.result.histogram(path, kind + "_").curve()

    def angular_pdf(self, species=None):
        """Angular-velocity distribution (whole cell, rescaled by sqrt(T_rot/I)): (c, P, error)
        and the kurtosis with its error, or None when the run has no angular_velocity_pdf or has
        smooth particles (beta = -1: the observable then writes only a note)."""
        path = f"observables/angular_velocity_pdf/{species or self.species[0]}"
        if path not in self.result.root:
            return None
        kurtosis = self.result.estimate(f"{path}/kurtosis")
        return self.result.histogram(f"{path}/z", "scaled_").curve(), *kurtosis

    def angular_kurtosis(self, species=None):
        """Kurtosis <c^4>/<c^2>^2 of the whole-cell angular velocities, with its error."""
        ang = self.angular_pdf(species)
        if ang is None:
            raise KeyError(f"{self.path.name}: no angular velocities (smooth particles?)")
        return ang[1], ang[2]

    def mixing_kurtosis(self, species=None):
        """Kurtosis the whole-cell angular velocities would have if they were Gaussian in every
        slab: 3 <n T_rot^2> <n> / <n T_rot>^2 over the slabs of the profiles (n the number
        density). The whole-cell distribution is rescaled by one T_rot while T_rot varies with
        y; this is the part of its kurtosis that the profile alone explains."""
        s = species or self.species[0]
        _, n, _ = self.profile(f"{s}/number_density")
        _, t, _ = self.profile(f"{s}/T_rot")
        return float(3 * np.sum(n * t**2) * np.sum(n) / np.sum(n * t) ** 2)

    def slab_scalar(self, centre, component, key, species=None):
        """A scalar of a slab distribution ('kurtosis', 'temperature')."""
        return self.result.number(f"{self.slab(centre)}/{species or self.species[0]}/{component}/"
                                  f"{key}")

    def restitution(self, key="alpha_1d"):
        """Histogram of the effective restitution ('alpha_1d', 'alpha_1d_tail', ...): (x, P, e),
        x the geometric bin centres of the logarithmic tail histograms."""
        h = self.result.histogram(f"{RESTITUTION}/{key}")
        x = np.sqrt(h.edges[1:] * h.edges[:-1]) if key.endswith("tail") else h.centres
        return x, h.density, h.error

    def conditional(self, g_value):
        """P(alpha_1d | g_x) at the conditional value g_x = g_value: (alpha_1d, P, error)."""
        for name, g in self.result.root[f"{RESTITUTION}/conditional"].items():
            if abs(g.attrs["g"] - g_value) < 1e-9:
                return self.restitution(f"conditional/{name}")
        raise KeyError(f"{self.path.name}: no conditional distribution at g = {g_value}")

    def fraction_above_one(self):
        """Fraction of collisions with alpha_1d > 1, with its error."""
        return tuple(self.result.estimate(f"{RESTITUTION}/fraction_above_one"))


class Results:
    """The result files of a study directory, opened on first use by point name."""

    def __init__(self, directory):
        self.directory = Path(directory)
        self._runs = {}

    def __getitem__(self, name):
        if name not in self._runs:
            path = self.directory / f"{name}.h5"
            if not path.exists():
                raise FileNotFoundError(f"{path} is missing: run the studies first "
                                        "(make reproduce-barrat-trizac-2002)")
            self._runs[name] = Run(path)
        return self._runs[name]


def second_moment(x, p, err):
    """<x^2> of a histogram density (bin centres x) over the histogram range, with its error
    (bin errors taken as independent)."""
    total = np.sum(p)
    m = np.sum(x**2 * p) / total
    return float(m), float(np.sqrt(np.sum(((x**2 - m) * err) ** 2)) / total)


def power_law_fit(x, p, err, lo, hi):
    """Weighted least-squares fit of log p = a + k log x over lo < x < hi: (k, error of k)."""
    sel = (x > lo) & (x < hi) & (p > 0) & (err > 0)
    if sel.sum() < MIN_FIT_POINTS:
        return float("nan"), float("nan")
    fit = power_law(x[sel], p[sel], err[sel])
    return fit.exponent, fit.exponent_error


def tail_exponent(run, lo=10.0, hi=1000.0):
    """Exponent of the alpha_1d tail (Fig. 8: alpha_1d^-2), fitted over lo < alpha_1d < hi.

    The error adds to the statistical one half the change of the exponent when the lower end of
    the fit moves up by a factor 3 (the approach to the asymptotic power law)."""
    tail = run.restitution("alpha_1d_tail")
    k, e = power_law_fit(*tail, lo, hi)
    k3, _ = power_law_fit(*tail, 3 * lo, hi)
    return k, float(np.hypot(e, 0.5 * (k - k3)))


def cutoff_exponent(data, g, u0=1.5):
    """Exponent q of P(alpha_1d | g_x) ~ exp(-(alpha_1d g_x)^q / R) at large alpha_1d (Fig. 9).

    Fitted where both alpha_1d and alpha_1d g_x exceed u0 (beyond the peak of P at the
    restitution coefficient and its shoulder); the error adds to the statistical one half the
    change of q when u0 goes from 1.5 to 2."""
    q, e = stretched_exponent_fit(*data, g=g, lo=max(u0, u0 / g))
    q2, _ = stretched_exponent_fit(*data, g=g, lo=max(u0 + 0.5, (u0 + 0.5) / g))
    return q, float(np.hypot(e, 0.5 * (q - q2)))


def stretched_exponent_fit(alpha, p, err, g, lo=1.0, min_counts=16):
    """Fit P(alpha|g) ~ C exp(-(alpha g)^q / R) for alpha > lo: the exponent q and its error.

    q = 2 is the Gaussian cut-off the paper finds next to vibrating walls, q = 1 the exponential
    one next to thermal walls (Fig. 9). For each q on a grid, log P is fitted linearly in
    (alpha g)^q with weights P / error; q minimises chi^2 and its error is where chi^2 (scaled
    by the reduced chi^2 when above 1) rises by 1. Bins with fewer than `min_counts` counts
    (relative error above 1/sqrt(min_counts)) are left out.
    """
    sel = (alpha > lo) & (p > 0) & (err > 0) & (err < p / np.sqrt(min_counts))
    if sel.sum() < MIN_FIT_POINTS:
        return float("nan"), float("nan")
    u, ly, w = alpha[sel] * g, np.log(p[sel]), p[sel] / err[sel]
    qs = np.arange(0.3, 4.0, 0.005)
    chi2 = np.array([_linear_chi2(u**q, ly, w) for q in qs])
    best = int(np.argmin(chi2))
    scale = max(chi2[best] / max(sel.sum() - 3, 1), 1.0)
    inside = qs[chi2 <= chi2[best] + scale]
    return float(qs[best]), float(0.5 * (inside.max() - inside.min()))


def _linear_chi2(x, y, w):
    """chi^2 of the weighted straight-line fit of y against x."""
    coef = np.polyfit(x, y, 1, w=w)
    return float(np.sum((w * (y - np.polyval(coef, x))) ** 2))


def l1_distance(pdf_a, pdf_b, cmax=4.0):
    """Integral of |P_a - P_b| over |c| < cmax for two histogram densities (c, P, error) on
    different bins (P_b is interpolated at the bin centres of P_a)."""
    c, pa, _ = pdf_a
    sel = np.abs(c) < cmax
    pb = np.interp(c[sel], pdf_b[0], pdf_b[1])
    return float(np.sum(np.abs(pa[sel] - pb)) * (c[1] - c[0]))


def l1_to_gaussian(pdf, cmax=4.0):
    """Integral of |P - G| over |c| < cmax, G the unit-variance Gaussian."""
    c = np.linspace(-cmax, cmax, 1601)
    g = np.exp(-c**2 / 2) / np.sqrt(2 * np.pi)
    return l1_distance(pdf, (c, g, g * 0), cmax)


def local_maxima(x, p, err, floor=0.02):
    """Positions of the significant local maxima of a histogram density.

    The density is smoothed over three bins; a maximum counts when it exceeds `floor` times the
    largest value and the smoothed density drops on both sides, before rising above it again,
    by more than three standard errors.
    """
    smooth = np.convolve(p, np.ones(3) / 3, "valid")
    x, err = x[1:-1], np.sqrt(np.convolve(err**2, np.ones(3) / 9, "valid"))
    peaks = []
    for i in range(1, len(smooth) - 1):
        top = smooth[i]
        if top < floor * smooth.max() or not (top >= smooth[i - 1] and top > smooth[i + 1]):
            continue
        if _drop(smooth[: i + 1][::-1], top, err[i]) and _drop(smooth[i:], top, err[i]):
            peaks.append(float(x[i]))
    return peaks


def _drop(side, top, top_err):
    """Whether the density falls significantly below `top` before rising above it again."""
    for v in side[1:]:
        if v > top:
            return False
        if top - v > 3 * top_err:
            return True
    return False
