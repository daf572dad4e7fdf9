#!/usr/bin/python3
"""Bhateja, Sharma & Singh, Phys. Fluids 28, 043301 (2016): measured numbers against the paper's.

Usage: /usr/bin/python3 studies/bhateja-2016/analysis.py [RESULTS_DIR]

Reads the study tables (`<study>.study.csv`, `lid-g0.fits.csv`) and per-run results (`<run>.h5`,
profiles) of the studies in this folder from RESULTS_DIR (default results/bhateja-2016) and writes
RESULTS_DIR/comparison.csv (`quantity,paper,measured,error,status,cause`, rewritten from scratch;
`status` and `cause` from verdicts.yaml, gran.comparison; the rows of diagnostics.py follow). `paper` is
the number the paper prints (read from paper.yaml), empty where the paper gives none; `error` is the
one-standard-error bar of `measured` (gran's jackknife block errors, fit covariances, propagated),
empty when there is none. A study whose results are missing is skipped with a note.

Conventions (README.md): Tbar = T_z / (m V_p^2) with T_z = m <w'^2> / 2 (Eq. (5)); the vertical
axis is z in 3D and y in 2D (gran names the component after the axis, so the 2D "T_z" of the paper
is gran's T_y). Three averages (DEFINITIONS): `volume` (mean of the slab temperatures over the bed,
the paper's Eq. (1)) and `particle` (each grain once), both about the local (slab, drive phase)
mean velocity, and `plain` (each grain once, about the centre-of-mass velocity).
Units: d, m, sqrt(d/g): W = V_p^2, T / (m g d) = T.
"""
import math
import sys
from pathlib import Path

import numpy as np
import yaml

from fitting import MODELS, fit_model
from gran import comparison
from gran.fits import power_law
from gran.studies import StudyFolder, read_fits

HERE = Path(__file__).resolve().parent
PAPER = yaml.safe_load((HERE / "paper.yaml").read_text())
LT = "observables.local_temperature."
# Temperature definitions: suffix of the scaled quantity, of the unscaled one.
#   volume: mean of the slab temperatures over the bed (Eq. (1)), about the slab-and-phase mean;
#   particle: each grain once, about the same local mean;
#   plain: each grain once, about the instantaneous centre-of-mass velocity of all grains (the
#   layers' collective motion counts as temperature; runs made before gran had it lack it).
DEFINITIONS = {"volume": ("_volume_scaled", "_volume"), "particle": ("_scaled", ""),
               "plain": ("_plain_scaled", "_plain")}
W_PAPER_END = PAPER["inferred"]["W_sweep_range"][1]  # 89.43: 4000 rpm, the end of the paper's sweep
W_ACCEPT = (10, 20, 50, 100)  # acceptance check of the brief
W2_TOLERANCE = 0.10  # W_2: smallest W beyond which Tbar stays within 10% of its value at max W
LIFT_OFF = 1.0  # W = Gamma for A = d: no lift-off below 1 (T_z = 0 in the paper up to W = 0.89)


# --- reading ----------------------------------------------------------------------------------

class Study:
    """The runs of one study: table rows, grouped by point, with the scaled temperatures."""

    def __init__(self, directory, name):
        self.directory, self.name = Path(directory), name
        try:
            self.folder = StudyFolder(self.directory, name)
        except FileNotFoundError as e:
            raise FileNotFoundError(f"{e} (make reproduce-bhateja-2016)") from None
        self.table = self.folder.table
        self.rows = self.table.rows

    def definitions(self):
        """The temperature definitions this study's runs report (vertical component)."""
        row = self.rows[0]
        return [d for d, (suffix, _) in DEFINITIONS.items()
                if row.get(LT + self.vertical(row) + suffix) not in (None, "")]

    def points(self):
        return self.table.points()

    @staticmethod
    def vertical(row):
        """Name of the vertical component: T_z (3D) or T_y (2D, vibration along y)."""
        return "T_z" if row.get(LT + "T_z") not in (None, "") else "T_y"

    def get(self, row, key):
        return self.table.value_and_error(row, key)

    def tbar(self, row, definition="volume", component=None):
        """Scaled temperature T_a / (m V_p^2) of a run: (value, error). component None: vertical;
        'T_x' horizontal; 'T' the mean over the d_f components."""
        c = component or self.vertical(row)
        return self.get(row, LT + c + DEFINITIONS[definition][0])

    def temperature(self, row, definition="volume", component=None):
        """Unscaled T_a in units m g d: (value, error)."""
        c = component or self.vertical(row)
        return self.get(row, LT + c + DEFINITIONS[definition][1])

    def w(self, row):
        """W = V_p^2/(d g) (NaN without gravity)."""
        return self.table.number(row, LT + "W")

    def vp(self, row):
        return self.table.number(row, LT + "peak_velocity")

    def runs(self, point):
        """The runs of a point sorted by V_p (= by W at fixed A)."""
        return sorted(self.table.runs(point), key=self.vp)

    def curve(self, point, definition="volume", component=None, scaled=True):
        """(W, value, error) arrays of one point."""
        runs = self.runs(point)
        f = self.tbar if scaled else self.temperature
        ve = np.array([f(r, definition, component) for r in runs]).reshape(-1, 2)
        return np.array([self.w(r) for r in runs]), ve[:, 0], ve[:, 1]

    def at(self, point, w, rel=0.01):
        """The run of a point at W (within rel)."""
        for r in self.runs(point):
            if abs(self.w(r) / w - 1) < rel:
                return r
        raise KeyError(f"{self.name}: no run of {point} at W = {w}")

    def profile(self, row):
        """Local profiles of a run: dict z, T (vertical, about the slab-and-phase mean), T_error,
        T_plain, T_plain_error (vertical, about the centre-of-mass velocity of all grains; NaN in
        results made before gran wrote it), phi, phi_error, grains, bed (mask of the slabs of
        gran's volume average), W, Vp."""
        with self.folder.run(row) as run:
            g = run.root["observables/local_temperature"]
            c = "T_z" if "T_z_profile" in g else "T_y"
            scene = run.scene
            obs = next(o for o in scene["observables"] if o["type"] == "local_temperature")
            grains = g["grains_per_slab"][:]
            occupancy = obs.get("min_occupancy", 0.1)
            top = np.nonzero(grains >= occupancy)[0]
            # gran's bed: the visited slabs from the lowest one up to the highest holding
            # >= min_occupancy grains; results older than that rule used the occupancy cut alone
            bed = (grains > 0) & (np.arange(len(grains)) <= (top[-1] if len(top) else -1))
            if bed.sum() != int(g["bed_slabs"][()]):
                bed = grains >= occupancy
            if bed.sum() != int(g["bed_slabs"][()]):
                raise ValueError(f"{row['run']}: cannot reconstruct the bed of the volume average")
            nan = np.full(len(grains), np.nan)
            plain = c + "_plain_profile"
            instant = c + "_instantaneous_profile"
            return {"z": g["z"][:], "T": g[c + "_profile"][:],
                    "T_error": g[c + "_profile_error"][:],
                    "T_plain": g[plain][:] if plain in g else nan,
                    "T_plain_error": g[plain + "_error"][:] if plain in g else nan,
                    "T_instant": g[instant][:] if instant in g else nan,
                    "phi": g["phi"][:],
                    "phi_error": g["phi_error"][:], "grains": grains, "bed": bed,
                    "W": float(g["W"][()]), "Vp": float(g["peak_velocity"][()])}


def load(directory, name):
    """A Study, or None (with a note) when its results are not there yet."""
    try:
        return Study(directory, name)
    except FileNotFoundError as e:
        print(f"skipped: {e}")
        return None


# --- derived quantities -----------------------------------------------------------------------

def peak(w, y):
    """W_f (argmax on the grid) and the index of the peak."""
    k = int(np.nanargmax(y))
    return w[k], k


def w2(w, y, tol=W2_TOLERANCE):
    """W_2: the smallest W beyond which Tbar stays within tol of its value at the largest W
    (searched from the peak on)."""
    _, k0 = peak(w, y)
    inside = np.abs(y / y[-1] - 1) <= tol
    k = len(w) - 1
    while k - 1 >= k0 and inside[k - 1]:
        k -= 1
    return w[k]


def alpha_over(w, vp, t, lo, hi):
    """alpha of T ~ V_p^alpha over lo <= W <= hi (T > 0): (alpha, error, points)."""
    m = (w >= lo * (1 - 1e-6)) & (w <= hi * (1 + 1e-6)) & (t > 0)
    fit = power_law(vp[m], t[m])
    return fit.exponent, fit.exponent_error, int(m.sum())


def ratio(a, ea, b, eb):
    """a / b and its error (independent errors)."""
    r = a / b
    return r, abs(r) * math.hypot(ea / a, eb / b)


def relchange(a, ea, b, eb):
    """(a - b) / b and its error."""
    r, e = ratio(a, ea, b, eb)
    return r - 1, e


# --- the comparison rows ----------------------------------------------------------------------

def table3_rows(sweeps):
    """Table III: a (1 + c W^-b) and a (1 + c e^-bW) on Tbar_z from W_f to the paper's end of the
    sweep (W <= 89.43) and to the end of ours (W <= 135), both temperature definitions."""
    paper = {(r["system"], r["fit"]): r for r in PAPER["fig8_table3"]["rows"]}
    rows = []
    for dim, study in sweeps.items():
        if study is None:
            continue
        point = f"sweep{dim.lower()}_rough"
        for definition in study.definitions():
            w, y, e = study.curve(point, definition)
            wf, _ = peak(w, y)
            for rng, hi in (("paper_range", W_PAPER_END), ("full_range", np.inf)):
                m = (w >= wf) & (w <= hi)
                for form in MODELS:
                    fit = fit_model(form, w[m], y[m], e[m])
                    ref = paper[(f"{dim} rough", form)]
                    tag = f"table3_{dim.lower()}_rough_{form}_{definition}_{rng}"
                    for k, par in enumerate("abc"):
                        rows.append((f"{tag}_{par}", ref[par], fit["p"][k], fit["err"][k]))
                    rows.append((f"{tag}_a_over_paper", None, fit["p"][0] / ref["a"],
                                 fit["err"][0] / ref["a"]))
                    rows.append((f"{tag}_R", ref["correlation"], math.sqrt(max(fit["r2"], 0)),
                                 None))
                    rows.append((f"{tag}_R2", None, fit["r2"], None))
                    rows.append((f"{tag}_chi2_reduced", None, fit["chi2_reduced"], None))
                    rows.append((f"{tag}_W_from", None, w[m][0], None))
                    rows.append((f"{tag}_W_to", None, w[m][-1], None))
                    rows.append((f"{tag}_points", None, fit["n"], None))
    return rows


def paper_algebraic(dim, w):
    """Tbar_z of the paper's algebraic Table III fit (rough, `dim` = '2D' or '3D')."""
    r = next(r for r in PAPER["fig8_table3"]["rows"]
             if r["system"] == f"{dim} rough" and r["fit"] == "algebraic")
    return r["a"] * (1 + r["c"] * w ** -r["b"])


def acceptance_rows(study, dim, points, prefix):
    """Tbar_z at W = 10, 20, 50, 100 against the paper's algebraic fit, with the relative
    deviation (measured - paper) / paper, every definition; `_times2_reldev` tests the
    hypothesis that the paper's T_z is m <w^2> (no 1/2), i.e. (2 measured - paper) / paper."""
    rows = []
    for point in points:
        for definition in study.definitions():
            for wt in W_ACCEPT:
                try:
                    run = study.at(point, wt)
                except KeyError:
                    continue
                v, e = study.tbar(run, definition)
                ref = paper_algebraic(dim, study.w(run))
                tag = f"{prefix}_{point}_{definition}_W{wt}"
                rows.append((tag, round(ref, 4), v, e))
                rows.append((tag + "_reldev", None, v / ref - 1, e / ref))
                # hypothesis, not a fit: the paper's T_z = m <w^2> (twice Eq. (5)'s m <w^2> / 2)
                rows.append((tag + "_times2_reldev", None, 2 * v / ref - 1, 2 * e / ref))
    return rows


def sweep_cases(sweeps):
    """(dim, case, study, point name) of every smooth and rough sweep that has results."""
    for dim, study in sweeps.items():
        if study is None:
            continue
        for case in ("smooth", "rough"):
            yield dim, case, study, f"sweep{dim.lower()}_{case}"


def fig2_rows(sweeps):
    """Fig. 2: W_f and the peak of Tbar_z per case, the decay after it (value at W = 85.01, the
    last of the paper's printed W before 89.43, over the peak) and the largest volume fraction at
    W_f (paper: "about 0.2")."""
    rows = []
    for dim, case, study, point in sweep_cases(sweeps):
        for definition in study.definitions():
            w, y, e = study.curve(point, definition)
            wf, k = peak(w, y)
            tag = f"fig2_{dim.lower()}_{case}_{definition}"
            rows.append((f"{tag}_W_f", None, wf, None))
            rows.append((f"{tag}_peak", None, y[k], e[k]))
            j = int(np.argmin(np.abs(w - 85.01)))
            rows.append((f"{tag}_T_W{w[j]:.4g}_over_peak", None,
                         *ratio(y[j], e[j], y[k], e[k])))
            j0 = int(np.argmin(np.abs(w - 0.894)))
            rows.append((f"{tag}_T_W{w[j0]:.3g}_unfluidized", 0, y[j0], e[j0]))
        w, y, _ = study.curve(point, "volume")
        prof = study.profile(study.runs(point)[peak(w, y)[1]])
        bed = prof["bed"]
        k = int(np.argmax(np.where(bed, prof["phi"], -1)))
        rows.append((f"fig2_{dim.lower()}_{case}_max_phi_profile_at_W_f", 0.2, prof["phi"][k],
                     prof["phi_error"][k]))
        rows.append((f"fig2_{dim.lower()}_{case}_bed_mean_phi_at_W_f", 0.2,
                     float(np.mean(prof["phi"][bed])), None))
    return rows


def table1_rows(sweeps):
    """Table I: alpha of T_z ~ V_p^alpha over the experiments' W ranges (rough systems). Warr's
    range 0.5-9 starts below lift-off (W < 1: no fluidisation, T_z ~ 0), so the fit uses W > 1;
    `warr_from_W2` (W 2-9) shows how much the barely fluidised W = 1.4 point weighs.
    The 3D ranges are drawn only on Fig. 2: measured left empty."""
    rows = []
    ref = {r["ref"].split(" (")[0]: r["alpha_paper"] for r in PAPER["table1"]["rows"]}
    s2 = sweeps.get("2D")
    if s2 is not None:
        for definition in s2.definitions():
            w, t, _ = s2.curve("sweep2d_rough", definition, scaled=False)
            vp = np.sqrt(w)  # V_p / sqrt(g d) = sqrt(W)
            for name, lo, hi, paper in (("warr", LIFT_OFF, 9, ref["Warr et al."]),
                                        ("feitosa_menon", 44, 135, ref["Feitosa and Menon"]),
                                        ("warr_from_W2", 2, 9, None),
                                        ("feitosa_menon_to_W89", 44, W_PAPER_END, None)):
                a, e, n = alpha_over(w, vp, t, lo, hi)
                rows.append((f"table1_alpha_{name}_2d_rough_{definition}", paper, a, e))
    for name in ("Wildman et al.", "Yang and Candela", "Windows-Yule and Parker"):
        key = name.split()[0].lower().replace("-", "_")
        rows.append((f"table1_alpha_{key}_3d_rough_range_not_in_text", ref[name], math.nan, None))
    return rows


def rest_height(directory, dim, case):
    """h_cm of the settled bed (rest-<dim>.yaml)."""
    rest = load(directory, f"rest-{dim.lower()}")
    if rest is None:
        return None
    run = rest.table.runs(f"rest{dim.lower()}_{case}")[0]
    return rest.get(run, "observables.barycentric_height.h_cm")


def table2_fig7_rows(directory, sweeps):
    """Table II (alpha_h of Delta h_cm = h_cm - h_rest ~ V_p^alpha_h over Warr's range, 2D rough)
    and Fig. 7 (Tbar_z / Delta hbar_cm, Delta hbar_cm = Delta h_cm / (V_p^2 / g), i.e.
    T_z / (m g Delta h_cm), at the paper's printed W)."""
    rows = []
    for dim, study in sweeps.items():
        if study is None:
            continue
        rest = rest_height(directory, dim, "rough")
        if rest is None:
            continue
        runs = study.runs(f"sweep{dim.lower()}_rough")
        w = np.array([study.w(r) for r in runs])
        h = np.array([study.get(r, "observables.barycentric_height.h_cm") for r in runs])
        dh, dh_err = h[:, 0] - rest[0], np.hypot(h[:, 1], rest[1])
        if dim == "2D":
            a, e, _ = alpha_over(w, np.sqrt(w), dh, LIFT_OFF, 9)
            rows.append(("table2_alpha_h_warr_2d_rough",
                         PAPER["table2"]["rows"][0]["alpha_h_paper"], a, e))
            a, e, _ = alpha_over(w, np.sqrt(w), dh, 2, 9)
            rows.append(("table2_alpha_h_warr_from_W2_2d_rough", None, a, e))
        for wt in (2.01, 5.58, 22.35, 50.3, 85.01, 135):
            k = int(np.argmin(np.abs(w - wt)))
            if abs(w[k] / wt - 1) > 0.01:
                continue
            for definition in study.definitions():
                t, te = study.temperature(runs[k], definition)
                rows.append((f"fig7_{dim.lower()}_rough_{definition}_Tz_over_mg_dh_W{wt}", None,
                             *ratio(t, te, dh[k], dh_err[k])))
        rows.append((f"fig7_{dim.lower()}_rough_h_rest", None, rest[0], None))
    for r in PAPER["table2"]["rows"][1:]:
        key = r["ref"].split()[0].lower().replace("-", "_")
        rows.append((f"table2_alpha_h_{key}_3d_rough_range_not_in_text", r["alpha_h_paper"],
                     math.nan, None))
    return rows


def lid_curve(study, point, definition):
    """lid-g0.yaml, one point: V_p, T_z (value, error) rows, sorted by V_p."""
    runs = sorted(study.runs(point), key=study.vp)
    return (np.array([study.vp(r) for r in runs]),
            np.array([study.temperature(r, definition) for r in runs]), runs)


def lid_alpha(study, point, definition):
    """alpha of T_z ~ V_p^alpha at g = 0 (OLS in log-log, as gran's study fits), its error and the
    log prefactor."""
    vp, t, _ = lid_curve(study, point, definition)
    fit = power_law(vp, t[:, 0])
    return fit.exponent, fit.exponent_error, fit.log_prefactor


def fig6_rows(directory):
    """Fig. 6: alpha of T_z ~ V_p^alpha with g = 0 under a lid, paper 2: gran's study fits
    (lid-g0.fits.csv: volume and particle averages), and the same OLS here for every definition
    (`_check` rows; the plain average has no study fit)."""
    study = load(directory, "lid-g0")
    path = Path(directory) / "lid-g0.fits.csv"
    rows = []
    paper = PAPER["fig6"]["result_alpha"]
    if path.exists():
        for fit in read_fits(path).values():
            definition = "particle" if fit.name.startswith("lid_alpha_particle") else "volume"
            rows.append((f"fig6_alpha_{fit.group or fit.name}_{definition}", paper, fit.theta,
                         fit.theta_error))
    if study is not None:
        for point in study.points():
            for d in study.definitions():
                a, e, _ = lid_alpha(study, point, d)
                rows.append((f"fig6_alpha_{point}_{d}_check", paper, a, e))
    return rows


def parameter_curves(directory, sweeps, definition="volume"):
    """Figs. 9-10: {point: (W, Vp, Tbar, Tbar error, T)} for the variants of parameters-2d.yaml and
    the canonical rough 2D system on the same W grid (from sweep-2d.yaml); {} when the runs lack
    the definition."""
    study = load(directory, "parameters-2d")
    if study is None or definition not in study.definitions():
        return {}
    out = {}
    for point in study.points():
        w, y, e = study.curve(point, definition)
        _, t, _ = study.curve(point, definition, scaled=False)
        out[point] = (w, np.sqrt(w), y, e, t)
    s2 = sweeps.get("2D")
    if s2 is not None and out:
        grid = next(iter(out.values()))[0]
        runs = [s2.at("sweep2d_rough", wv) for wv in grid]
        y = np.array([s2.tbar(r, definition) for r in runs])
        t = np.array([s2.temperature(r, definition)[0] for r in runs])
        out["par2d_canonical"] = (grid, np.sqrt(grid), y[:, 0], y[:, 1], t)
    return out


def parameter_alphas(curves):
    """{point: (W_f, W_2, alpha, alpha error, points)}: T ~ V_p^alpha over [W_f, W_2]."""
    out = {}
    for point, (w, vp, y, _, t) in curves.items():
        wf, wtwo = peak(w, y)[0], w2(w, y)
        out[point] = (wf, wtwo, *alpha_over(w, vp, t, wf, wtwo))
    return out


def fig9_10_rows(curves, definition):
    """alpha over [W_f, W_2] per variant; k_n effect; the trends in e_p and N (rows tagged with
    the temperature definition)."""
    rows, alpha = [], {}
    if not curves:
        return rows
    for point, (wf, wtwo, a, ae, n) in sorted(parameter_alphas(curves).items()):
        alpha[point] = (a, ae)
        paper = PAPER["fig10"]["alpha_deep_bed"] if point in ("par2d_N6", "par2d_N8") else None
        rows += [(f"fig10_{point}_{definition}_W_f", None, wf, None),
                 (f"fig10_{point}_{definition}_W_2", None, wtwo, None),
                 (f"fig10_{point}_{definition}_alpha_Wf_W2", paper, a, ae),
                 (f"fig10_{point}_{definition}_alpha_points", None, n, None)]
    if "par2d_canonical" in curves:
        w0, _, y0, e0, _ = curves["par2d_canonical"]
        for kn in ("par2d_kn2e4", "par2d_kn2e6"):
            if kn in curves:
                m = w0 > LIFT_OFF
                dev = np.abs(curves[kn][2][m] / y0[m] - 1)
                k = int(np.argmax(dev))
                yk, ek = curves[kn][2][m][k], curves[kn][3][m][k]
                err = ratio(yk, ek, y0[m][k], e0[m][k])[1]
                rows.append((f"fig9a_{kn}_{definition}_max_rel_diff_vs_kn2e5", 0, dev[k], err))
    order = {"e_p": ("par2d_e0.7", "par2d_e0.8", "par2d_canonical", "par2d_e0.95"),
             "N": ("par2d_N2", "par2d_N3", "par2d_canonical", "par2d_N6", "par2d_N8"),
             "mu_p": ("par2d_mu0.1", "par2d_canonical", "par2d_mu0.8")}
    for par, pts in order.items():
        a = [alpha[p][0] for p in pts if p in alpha]
        if len(a) > 1:
            rows.append((f"fig10_alpha_{par}_{definition}_monotonic_increasing", None,
                         int(all(np.diff(a) > 0)), None))
            rows.append((f"fig10_alpha_{par}_{definition}_monotonic_decreasing", None,
                         int(all(np.diff(a) < 0)), None))
            rows.append((f"fig10_alpha_{par}_{definition}_range_max_minus_min", None,
                         max(a) - min(a), None))
    if "par2d_N3" in alpha and "par2d_canonical" in alpha:
        rows.append((f"fig10_alpha_N4_minus_N3_{definition}", 0,
                     alpha["par2d_canonical"][0] - alpha["par2d_N3"][0],
                     math.hypot(alpha["par2d_canonical"][1], alpha["par2d_N3"][1])))
    return rows


def fig11_data(directory):
    """amplitude-2d.yaml: {(A/d, W): (T_z/(m g d) value, error)} for both definitions."""
    study = load(directory, "amplitude-2d")
    if study is None:
        return None
    out = {d: {} for d in study.definitions()}
    for r in study.rows:
        # the points are named after A/d and W (amp2d_A1_W4.52): the same numbers from the table
        amp, wv = study.table.number(r, "drivers.0.amplitude"), round(study.w(r), 2)
        for d in study.definitions():
            out[d][(amp, wv)] = study.temperature(r, d)
    return out


def fig11_rows(data):
    """Fig. 11: mean relative change of T_z/(m g d) from A/d = 1 to 0.1 (paper -15%), mean
    |change| within A/d 0.1-0.5 (paper 3%), and along W 4.52 -> 8.04 at A/d = 1 (paper +50%)."""
    if data is None:
        return []
    res = PAPER["fig11"]["results"]
    rows = []
    for d, t in data.items():
        ws = sorted({w for _, w in t})

        def mean_change(a_to, a_from, absolute=False):
            ch = [relchange(*t[(a_to, w)], *t[(a_from, w)]) for w in ws]
            v = [abs(c[0]) if absolute else c[0] for c in ch]
            return float(np.mean(v)), math.sqrt(sum(c[1] ** 2 for c in ch)) / len(ch)

        rows.append((f"fig11_{d}_mean_relchange_A1_to_A0.1",
                     -res["dashed_decrease_A_1_to_0.1_percent"] / 100, *mean_change(0.1, 1)))
        rows.append((f"fig11_{d}_mean_abs_relchange_A0.1_to_A0.5",
                     res["dashed_change_A_0.1_to_0.5_percent"] / 100,
                     *mean_change(0.5, 0.1, absolute=True)))
        rows.append((f"fig11_{d}_relchange_W4.52_to_W8.04_A1",
                     res["solid_increase_percent"] / 100, *relchange(*t[(1.0, ws[-1])],
                                                                    *t[(1.0, ws[0])])))
    return rows


def engines_rows(directory):
    """engines-2d.yaml: T_z of the DEM runs (k_n = 2e3 ... 2e6) over the event-driven one, per W."""
    study = load(directory, "engines-2d")
    if study is None:
        return []
    rows = []
    for ref in study.runs("engines_event_driven"):
        wv = study.w(ref)
        for point in study.points():
            if point == "engines_event_driven":
                continue
            try:
                run = study.at(point, wv)
            except KeyError:
                continue
            for d in study.definitions():
                name = point.removeprefix("engines_")
                rows.append((f"engines_{name}_over_event_driven_{d}_W{wv:.3g}", None,
                             *ratio(*study.tbar(run, d), *study.tbar(ref, d))))
    return rows


PROFILE_KEYS = (("", "T"), ("_plain", "T_plain"))  # row infix, profile key: local, plain


def hottest(p, key="T"):
    """Index of the hottest bed slab of a profile (key "T": local, "T_plain": about the centre of
    mass), or None when the profile is missing."""
    t = np.where(p["bed"], p[key], -np.inf)
    return None if not np.any(np.isfinite(t) & p["bed"]) else int(np.nanargmax(t))


def hottest_rows(tag, p, paper=None):
    """Height of the hottest bed slab, local and plain profile (error: half a slab), and the mean
    temperature of the bed slabs 7-10 d above the base (where the paper puts the hottest region
    of shallow smooth beds at W = 22.35) over that maximum (1 if the paper's window held it)."""
    rows = []
    for infix, key in PROFILE_KEYS:
        k = hottest(p, key)
        if k is None:
            continue
        rows.append((f"{tag}{infix}_hottest_slab_z", paper, p["z"][k], 0.5))
        window = p["bed"] & (p["z"] >= 7) & (p["z"] <= 10)
        if window.any():
            mean = float(np.mean(p[key][window]))
            mean_err = math.sqrt(float(np.sum(p[key + "_error"][window] ** 2))) / window.sum()
            rows.append((f"{tag}{infix}_T_z7-10_over_max", None,
                         *ratio(mean, mean_err, p[key][k], p[key + "_error"][k])))
    return rows


def profile_rows(directory, sweeps):
    """Figs. 12-16: height of the hottest slab (bed slabs only) of the local profile (about the
    slab-and-phase mean) and of the plain profile (about the centre-of-mass velocity) at
    W = 22.35 for N = 4, 6, 8 (paper 7-10 d for shallow smooth beds); same for the N = 4 smooth
    and rough 3D sweep at the W of Figs. 12-13, with the densest slab (Fig. 15)."""
    rows = []
    paper = "7-10"  # Sec. VI, Fig. 12(b): smooth 3D, shallow beds, W = 22.35
    study = load(directory, "profiles-3d")
    if study is not None:
        for point in study.points():
            try:
                run = study.at(point, 22.35)
            except KeyError:
                continue
            rows += hottest_rows(f"fig12_W22.35_{point}", study.profile(run),
                                 paper if point.endswith("N4") else None)
    s3 = sweeps.get("3D")
    if s3 is not None:
        for case in ("smooth", "rough"):
            for wt in (5.58, 22.35, 50.3, 85.01):
                p = s3.profile(s3.at(f"sweep3d_{case}", wt))
                rows += hottest_rows(f"fig14_3d_{case}_W{wt}", p,
                                     paper if (case, wt) == ("smooth", 22.35) else None)
                j = int(np.argmax(np.where(p["bed"], p["phi"], -1)))
                rows.append((f"fig15_3d_{case}_W{wt}_densest_slab_z", None, p["z"][j], 0.5))
    return rows


def lid_rows(sweeps):
    """The open top is an elastic wall (2D: 300 d, 3D: 100 d above the base): hits on it per unit
    time over hits on the base, at W = 85.01 (near the end of the paper's sweep) and the largest
    W of each case (0 = never reached), and the largest ratio over the sweep with its W."""
    rows = []
    for dim, case, study, point in sweep_cases(sweeps):
        tag = f"top_wall_hits_over_base_hits_{dim.lower()}_{case}"
        values = []
        for run in study.runs(point):
            up = study.get(run, "observables.wall_pressure.upper.collision_frequency")
            low = study.get(run, "observables.wall_pressure.lower.collision_frequency")
            values.append((study.w(run), *(ratio(*up, *low) if up[0] > 0 else (0.0, None))))
        for run in (study.at(point, 85.01), study.runs(point)[-1]):
            wv = study.w(run)
            _, v, e = next(x for x in values if x[0] == wv)
            rows.append((f"{tag}_W{wv:.3g}", None, v, e))
        wv, v, e = max(values, key=lambda x: x[1])
        rows.append((f"{tag}_max_over_sweep", None, v, e))
        rows.append((f"{tag}_max_over_sweep_W", None, wv, None))
    return rows


def all_rows(directory):
    sweeps = {"2D": load(directory, "sweep-2d"), "3D": load(directory, "sweep-3d")}
    rows = table3_rows(sweeps)
    if sweeps["3D"] is not None:
        rows += acceptance_rows(sweeps["3D"], "3D", ["sweep3d_rough"], "accept_3d")
    if sweeps["2D"] is not None:
        rows += acceptance_rows(sweeps["2D"], "2D", ["sweep2d_rough"], "accept_2d")
    sens = load(directory, "sensitivity-3d")
    if sens is not None:
        rows += acceptance_rows(sens, "3D", sens.points(), "accept_3d")
    rows += fig2_rows(sweeps)
    rows += table1_rows(sweeps)
    rows += table2_fig7_rows(directory, sweeps)
    rows += fig6_rows(directory)
    for d in DEFINITIONS:
        rows += fig9_10_rows(parameter_curves(directory, sweeps, d), d)
    rows += fig11_rows(fig11_data(directory))
    rows += engines_rows(directory)
    rows += profile_rows(directory, sweeps)
    rows += lid_rows(sweeps)
    return rows


def main():
    import diagnostics  # the open points of issue 16 (it reads through this module)
    directory = Path(sys.argv[1] if len(sys.argv) > 1 else "results/bhateja-2016")
    rows = all_rows(directory) + diagnostics.rows(directory)
    verdicts = comparison.Verdicts.load(HERE / "verdicts.yaml")
    comparison.write(rows, directory / "comparison.csv", verdicts=verdicts)
    comparison.report(rows, verdicts, directory / "comparison.csv")


if __name__ == "__main__":
    main()
