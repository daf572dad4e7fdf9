"""Reading the McNamara & Falcon 2005 study results, and the physics the figures and checks share.

`Sweep` reads the table and the power-law fits of sweep.yaml (`sweep.study.csv`,
`sweep.fits.csv`, through gran.studies); `Snapshot` one run of snapshots.yaml (trajectory frames and
the vertical density profile, through gran.results). The rest is plain physics: the restitution
law of Eq. (1), the piston's position (two joined parabolas), and the local packing fraction of
every disk of a frame from its Voronoi cell, which the Fig. 3 cluster criterion uses.
"""
import math
from pathlib import Path

import matplotlib.tri as mtri
import numpy as np

from gran.results import Run
from gran.studies import StudyFolder

# The five cases of sweep.yaml: point name -> (gravity on, restitution as in the paper's panels).
CASES = {
    "g_rv": (True, "r = r(v)"),
    "g_r0.95": (True, "r = 0.95"),
    "g_r0.7": (True, "r = 0.7"),
    "g0_rv": (False, "r = r(v)"),
    "g0_r0.95": (False, "r = 0.95"),
}
QUANTITIES = ("T", "Nc", "dI", "P")  # the four exponents of Fig. 4, named as in the fits
LAYER = 100  # particles per layer: n = N d / L with d = 2 mm, L = 20 cm
WALL = "observables.wall_pressure"


def restitution(v, r0=0.95, v0=0.3):
    """Eq. (1): r(v) = 1 - (1 - r0)(v/v0)^(1/5) for v <= v0, r0 (v/v0)^(-1/4) for v >= v0."""
    x = np.asarray(v, dtype=float) / v0
    return np.where(x <= 1, 1 - (1 - r0) * np.abs(x) ** 0.2, r0 * np.maximum(x, 1) ** -0.25)


def piston_height(t, amplitude, frequency):
    """Height of the piston (two joined parabolas, phase 0) above its lowest position at time t.

    Parabola k is centred on t_k = k/(2f) and lasts |t - t_k| <= t0 = 1/(4f):
    z = s (A/2)((t - t_k)^2/t0^2 - 1), s = +1 for even k (around the lowest point), -1 for odd k;
    the height is A/2 + z, 0 at t = k/f (as in libgran/core/wall_motion.hpp)."""
    k = np.floor(2 * frequency * np.asarray(t) + 0.5)
    dt, t0 = np.asarray(t) - k / (2 * frequency), 1 / (4 * frequency)
    s = np.where(k % 2 == 0, 1.0, -1.0)
    return amplitude / 2 + s * (amplitude / 2) * (dt**2 / t0**2 - 1)


def voronoi_areas(points, width, floor, ceiling):
    """Area of the Voronoi cell of every disk centre in a box periodic in x (period `width`) and
    bounded by flat walls at y = floor and y = ceiling.

    The walls enter through mirror images (a cell next to a wall ends on it) and the periodic
    boundary through copies shifted by +-width; the cells are built from the Delaunay
    triangulation (matplotlib's qhull): the vertices of a cell are the circumcentres of the
    triangles around its point."""
    n = len(points)
    base = np.vstack([points, points + [-width, 0], points + [width, 0]])
    below, above = base.copy(), base.copy()
    below[:, 1] = 2 * floor - below[:, 1]
    above[:, 1] = 2 * ceiling - above[:, 1]
    pts = np.vstack([base, below, above])
    tri = mtri.Triangulation(pts[:, 0], pts[:, 1]).triangles
    a, b, c = (pts[tri[:, k]] for k in range(3))
    det = 2 * (a[:, 0] * (b[:, 1] - c[:, 1]) + b[:, 0] * (c[:, 1] - a[:, 1])
               + c[:, 0] * (a[:, 1] - b[:, 1]))
    sa, sb, sc = (np.sum(q * q, axis=1) for q in (a, b, c))
    cx = (sa * (b[:, 1] - c[:, 1]) + sb * (c[:, 1] - a[:, 1]) + sc * (a[:, 1] - b[:, 1])) / det
    cy = (sa * (c[:, 0] - b[:, 0]) + sb * (a[:, 0] - c[:, 0]) + sc * (b[:, 0] - a[:, 0])) / det
    owner = tri.ravel()
    triangle = np.repeat(np.arange(len(tri)), 3)
    order = np.argsort(owner, kind="stable")
    owner, triangle = owner[order], triangle[order]
    starts = np.searchsorted(owner, np.arange(n + 1))
    areas = np.empty(n)
    for i in range(n):
        t = triangle[starts[i]:starts[i + 1]]
        x, y = cx[t] - points[i, 0], cy[t] - points[i, 1]
        o = np.argsort(np.arctan2(y, x))
        x, y = x[o], y[o]
        areas[i] = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    return areas


class Sweep:
    """The runs and fits of sweep.yaml in a result folder."""

    def __init__(self, directory):
        self.directory = Path(directory)
        try:
            self.study = StudyFolder(self.directory, "sweep")
        except FileNotFoundError as e:
            raise FileNotFoundError(f"{e} (make reproduce-mcnamara-falcon-2005)") from None
        if not self.study.fits:
            raise FileNotFoundError(f"{self.directory / 'sweep.fits.csv'} is missing: run the "
                                    "study first (make reproduce-mcnamara-falcon-2005)")
        self.table = self.study.table

    def run(self, case, n, f):
        """The table row of one run (case, n layers, frequency f [Hz])."""
        for row in self.table.runs(case):
            if (int(row["species.0.count"]) == round(n * LAYER)
                    and int(row["drivers.0.frequency"]) == f):
                return row
        raise KeyError(f"no run {case}, n = {n}, f = {f} Hz in {self.directory}")

    def layers(self, case):
        """The n values swept for a case, sorted."""
        return sorted({int(r["species.0.count"]) / LAYER for r in self.table.runs(case)})

    def frequencies(self, case):
        """The frequencies [Hz] swept for a case, sorted."""
        return sorted({int(r["drivers.0.frequency"]) for r in self.table.runs(case)})

    def value(self, row, quantity):
        """A summary quantity of a run and its error (NaN when not reported)."""
        return self.table.value_and_error(row, quantity)

    def pressure_vs_n(self, case, f, wall="upper"):
        """Time-averaged pressure [N/m] on a wall against n at frequency f: (n, P, error)."""
        n = np.array(self.layers(case))
        pe = np.array([self.value(self.run(case, k, f), f"{WALL}.{wall}.pressure") for k in n])
        return n, pe[:, 0], pe[:, 1]

    def momentum_balance(self, case, n, f):
        """P_lower / (P_upper + N m g / L) of one run and its error.

        gran reports weight_per_area only under gravity; it is 0 without. The error treats the
        two pressures as independent, an upper bound: both come from the same trajectory."""
        row = self.run(case, n, f)
        lower, e_lower = self.value(row, f"{WALL}.lower.pressure")
        upper, e_upper = self.value(row, f"{WALL}.upper.pressure")
        weight = self.value(row, f"{WALL}.weight_per_area")[0]
        if math.isnan(weight):
            if CASES[case][0]:
                raise ValueError(f"{row['run']}: no weight_per_area under gravity")
            weight = 0.0
        return lower / (upper + weight), math.hypot(e_lower, e_upper) / (upper + weight)

    def exponent(self, case, quantity, n):
        """The fit of X ~ V^theta (X = T, Nc, dI, P) at n layers (gran.studies.StudyFit: theta,
        theta_error, max_deviation, valid False when a point deviates by 0.25 or more in log)."""
        return self.study.fit(f"theta_{quantity}_{case}_count{round(n * LAYER)}")

    def exponents(self, case, quantity):
        """theta(n) of one quantity: (n, theta, error, valid) arrays."""
        n = np.array(self.layers(case))
        fits = [self.exponent(case, quantity, k) for k in n]
        return (n, np.array([f.theta for f in fits]), np.array([f.theta_error for f in fits]),
                np.array([f.valid for f in fits]))


class Snapshot:
    """One run of snapshots.yaml: frames, the piston, the profile, local packing fractions."""

    def __init__(self, path):
        self.path = Path(path)
        if not self.path.exists():
            raise FileNotFoundError(f"{self.path} is missing: run snapshots.yaml first "
                                    "(make reproduce-mcnamara-falcon-2005)")
        self.run = Run.open(self.path)
        self.scene = self.run.scene
        self.width, self.height = (float(x) for x in self.run.box_lengths)
        self.diameter = float(self.scene["species"][0]["diameter"])
        self.amplitude = self.run.number("drivers/vibrating_wall/amplitude")
        self.frequency = self.run.number("drivers/vibrating_wall/frequency")

    @property
    def frames(self):
        """Number of stored frames."""
        return self.run.frames

    def positions(self, k):
        """Disk centres of frame k, shape (N, 2) [m]."""
        return self.run.positions(k)

    def time(self, k):
        """Time of frame k [s]."""
        return self.run.frame_time(k)

    def piston(self, k):
        """Piston height at frame k [m] (0: its lowest position)."""
        return float(piston_height(self.time(k), self.amplitude, self.frequency))

    def local_packing_fraction(self, k):
        """Packing fraction of every disk's Voronoi cell at frame k: (pi d^2/4) / cell area.
        The floor of the cells is the piston, their ceiling the lid."""
        cells = voronoi_areas(self.positions(k), self.width, self.piston(k), self.height)
        return np.pi * self.diameter**2 / 4 / cells

    def dense_fraction(self, threshold):
        """Per frame, the fraction of disks whose Voronoi packing fraction exceeds threshold."""
        return np.array([np.mean(self.local_packing_fraction(k) > threshold)
                         for k in range(self.frames)])

    def upper_half_fraction(self):
        """Per frame, the fraction of disk centres in the upper half of the chamber (between the
        piston, at its lowest in every frame, and the lid)."""
        return np.array([np.mean(self.positions(k)[:, 1] > 0.5 * (self.piston(k) + self.height))
                         for k in range(self.frames)])

    def profile(self):
        """Time-averaged packing fraction against height: (y [m], phi, error)."""
        return self.run.profile("observables/profiles/steel/packing_fraction")


def mean_and_error(samples):
    """Mean of per-frame values and its standard error (frames taken as independent)."""
    samples = np.asarray(samples, dtype=float)
    return float(samples.mean()), float(samples.std(ddof=1) / np.sqrt(len(samples)))
