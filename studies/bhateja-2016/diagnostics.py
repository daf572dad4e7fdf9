"""Bhateja et al. 2016: the open points of issue 16, diagnosed with runs (README.md, "Verdicts").

Rows for comparison.csv (analysis.py adds them):
- `ct_scan_*`: Table III and Fig. 2 against the unstated tangential damping c_t (ct-scan-3d.yaml,
  c_t = c_n from sweep-3d.yaml) for every temperature definition, and which combinations fit the
  paper's shape (b and c of the algebraic form) and magnitude (the four acceptance W);
- `table1_alpha_window_*`: alpha of T_z ~ V_p^alpha of the 3D rough sweep over W windows (the
  paper's 3D ranges are drawn only on its Fig. 2, which the seeds do not hold);
- `profile_peak_*`: the height of the maximum of four profiles at the paper's stations: the local
  temperature T(z) (about the slab-and-phase mean), the plain one (about the centre of mass), the
  instantaneous one (about the slab's mean velocity at each sample: a slab of one or two grains
  reads low), and the slab's kinetic energy per grain of the whole bed n(z) T(z) / N (a
  density-weighted "temperature" that, unlike T, vanishes above the bed);
- `fig5_*`: the horizontally vibrated channel (fig5.yaml, channel-full-3d.yaml).
"""
import math

import numpy as np

from analysis import (W_ACCEPT, W_PAPER_END, PAPER, load, paper_algebraic, peak,
                      ratio)
from fitting import fit_model
from gran.fits import power_law

CT_POINTS = (("0", "ct-scan-3d", "ct3d_ct0"), ("0.25", "ct-scan-3d", "ct3d_ct0.25"),
             ("0.5", "ct-scan-3d", "ct3d_ct0.5"), ("1", "sweep-3d", "sweep3d_rough"),
             ("2", "ct-scan-3d", "ct3d_ct2"))
SHAPE_SIGMAS = 2.0     # b and c of the algebraic fit within 2 standard errors of the paper's
MAGNITUDE_BAND = 0.15  # every acceptance W within 15% of the paper's curve (the brief's goal)


def _table3(form):
    return next(r for r in PAPER["fig8_table3"]["rows"]
                if r["system"] == "3D rough" and r["fit"] == form)


def ct_scan_rows(directory):
    """Per c_t and definition: the algebraic and exponential Table III fits over W_f <= W <= 89.43
    (a / paper, b, c), the deviation of b and c from the paper's in standard errors, W_f, the
    decay Tbar(85.01) / peak (Fig. 2: rough decays more slowly than smooth), the acceptance
    deviations x1 and x2, and two verdicts: `shape_fits` (b and c within SHAPE_SIGMAS) and
    `magnitude_fits` / `magnitude_x2_fits` (all four W within MAGNITUDE_BAND)."""
    rows = []
    studies = {name: load(directory, name) for name in ("ct-scan-3d", "sweep-3d")}
    for ct, name, point in CT_POINTS:
        study = studies[name]
        if study is None:
            continue
        for definition in study.definitions():
            w, y, e = study.curve(point, definition)
            tag = f"ct_scan_3d_rough_ct{ct}_{definition}"
            wf, k = peak(w, y)
            rows.append((f"{tag}_W_f", None, wf, None))
            j = int(np.argmin(np.abs(w - 85.01)))
            rows.append((f"{tag}_T_W85_over_peak", None, *ratio(y[j], e[j], y[k], e[k])))
            m = (w >= wf) & (w <= W_PAPER_END)
            shape_ok = False
            for form in ("algebraic", "exponential"):
                fit = fit_model(form, w[m], y[m], e[m])
                ref = _table3(form)
                rows.append((f"{tag}_{form}_a_over_paper", None, fit["p"][0] / ref["a"],
                             fit["err"][0] / ref["a"]))
                pulls = []
                for i, par in ((1, "b"), (2, "c")):
                    rows.append((f"{tag}_{form}_{par}", ref[par], fit["p"][i], fit["err"][i]))
                    pull = (fit["p"][i] - ref[par]) / fit["err"][i] if fit["err"][i] > 0 else math.inf
                    pulls.append(abs(pull))
                    rows.append((f"{tag}_{form}_{par}_pull", None, pull, None))
                if form == "algebraic":
                    shape_ok = max(pulls) <= SHAPE_SIGMAS
            rows.append((f"{tag}_shape_fits", None, float(shape_ok), None))
            dev1, dev2 = [], []
            for wt in W_ACCEPT:
                jj = int(np.argmin(np.abs(w / wt - 1)))
                if abs(w[jj] / wt - 1) > 0.01:
                    continue
                ref = paper_algebraic("3D", w[jj])
                dev1.append(y[jj] / ref - 1)
                dev2.append(2 * y[jj] / ref - 1)
                rows.append((f"{tag}_W{wt}_reldev", None, dev1[-1], e[jj] / ref))
                rows.append((f"{tag}_W{wt}_times2_reldev", None, dev2[-1], 2 * e[jj] / ref))
            if len(dev1) == len(W_ACCEPT):
                rows.append((f"{tag}_magnitude_fits", None,
                             float(max(map(abs, dev1)) <= MAGNITUDE_BAND), None))
                rows.append((f"{tag}_magnitude_x2_fits", None,
                             float(max(map(abs, dev2)) <= MAGNITUDE_BAND), None))
    return rows


WINDOWS = ((1.4, 4.52), (2.01, 8.04), (2.74, 10), (4.52, 16), (5.58, 20), (8.04, 28), (10, 44),
           (16, 50.3), (20, 68.46), (28, 100), (44, 135), (2.74, 89.43))


def table1_window_rows(directory):
    """alpha of T_z ~ V_p^alpha of the 3D rough canonical sweep over windows of W (the paper's
    Wildman, Yang-Candela and Windows-Yule-Parker ranges are drawn only on Fig. 2): a reader with
    the figure picks the row of the range; and, per paper value, the windows that give it within
    one standard error."""
    study = load(directory, "sweep-3d")
    if study is None:
        return []
    rows = []
    for definition in study.definitions():
        w, t, _ = study.curve("sweep3d_rough", definition, scaled=False)
        vp = np.sqrt(w)
        for lo, hi in WINDOWS:
            mask = (w >= lo * (1 - 1e-6)) & (w <= hi * (1 + 1e-6)) & (t > 0)
            if mask.sum() < 3:
                continue
            fit = power_law(vp[mask], t[mask])
            rows.append((f"table1_alpha_window_3d_rough_W{lo:g}-{hi:g}_{definition}", None,
                         fit.exponent, fit.exponent_error))
    return rows


STATIONS = (("profiles-3d", "prof3d_N4", 5.58), ("profiles-3d", "prof3d_N4", 22.35),
            ("profiles-3d", "prof3d_N6", 22.35), ("profiles-3d", "prof3d_N8", 22.35),
            ("profiles-3d", "prof3d_N4", 50.3), ("sweep-3d", "sweep3d_smooth", 85.01),
            ("sweep-3d", "sweep3d_rough", 22.35), ("sweep-3d", "sweep3d_rough", 85.01))


def weighted_profile(p):
    """The kinetic energy of a slab's grains per grain of the bed, n(z) T(z) / N: grains per slab
    times the local T, over the grains of the bed (it vanishes where the grains do)."""
    return p["grains"] * p["T"] / np.sum(p["grains"])


def profile_peak_rows(directory):
    """Height of the maximum of T(z) (local), T_plain(z) and n(z) T(z) / N over the slabs grains
    visit, and of the densest slab, at the paper's stations (Figs. 12-14); `_top_over_max`: the
    weighted profile in the highest visited slab over its maximum (the paper's profiles "decay to
    zero with height")."""
    rows = []
    studies = {}
    for name, point, wt in STATIONS:
        if name not in studies:
            studies[name] = load(directory, name)
        study = studies[name]
        if study is None:
            continue
        try:
            p = study.profile(study.at(point, wt))
        except KeyError:
            continue
        visited = p["grains"] > 0
        tag = f"profile_peak_{point}_W{wt}"
        paper = "7-10" if (point, wt) == ("prof3d_N4", 22.35) else None
        for key, values in (("local_T", p["T"]), ("plain_T", p["T_plain"]),
                            ("instantaneous_T", p["T_instant"]),
                            ("energy_density", weighted_profile(p))):
            if not np.any(np.isfinite(values) & visited):
                continue  # results made before gran wrote this profile
            v = np.where(visited & np.isfinite(values), values, -np.inf)
            k = int(np.argmax(v))
            rows.append((f"{tag}_{key}_max_z", paper, p["z"][k], 0.5))
            top = np.nonzero(visited)[0][-1]
            rows.append((f"{tag}_{key}_top_over_max", None, values[top] / values[k], None))
        j = int(np.argmax(np.where(visited, p["phi"], -1)))
        rows.append((f"{tag}_densest_slab_z", None, p["z"][j], 0.5))
    return rows


def fig5_rows(directory):
    """Fig. 5: per gravity case and definition, W_f and the peak of Tbar_z, the value at the largest
    W over the peak, the largest local maximum after the peak (the paper's second, smaller peak)
    and the lid hits per base hit where it sits; without gravity, alpha of T_z ~ V_p^alpha (2 for
    a constant Tbar_z) and the spread of Tbar_z over W. The full-size runs over the slice's."""
    study = load(directory, "fig5")
    rows = []
    if study is None:
        return rows
    for point in study.points():
        case = point.split("_")[-1]
        runs = study.runs(point)
        w = np.array([study.table.number(r, "drivers.vibrating_box.peak_velocity") ** 2
                      for r in runs])  # W = V_p^2 / (d g) with the nominal g = 1
        lid = np.array([study.table.number(r, "drivers.vibrating_box.hits_z_upper") /
                        max(study.table.number(r, "drivers.vibrating_box.hits_z_lower"), 1)
                        for r in runs])
        for definition in study.definitions():
            ve = np.array([study.tbar(r, definition) for r in runs])
            y, e = ve[:, 0], ve[:, 1]
            tag = f"fig5_{case}_{definition}"
            wf, k = peak(w, y)
            rows.append((f"{tag}_W_f", None, wf, None))
            rows.append((f"{tag}_peak", None, y[k], e[k]))
            rows.append((f"{tag}_T_Wmax_over_peak", None, *ratio(y[-1], e[-1], y[k], e[k])))
            later = [j for j in range(k + 1, len(y) - 1) if y[j] > y[j - 1] and y[j] > y[j + 1]]
            if later:
                j = max(later, key=lambda i: y[i])
                rows.append((f"{tag}_second_peak_W", None, w[j], None))
                rows.append((f"{tag}_second_peak_over_peak", None,
                             *ratio(y[j], e[j], y[k], e[k])))
                rows.append((f"{tag}_lid_hits_per_base_hit_at_second_peak", None, lid[j], None))
            if case == "g0":
                t = np.array([study.temperature(r, definition)[0] for r in runs])
                fit = power_law(np.sqrt(w), t)
                rows.append((f"{tag}_alpha", 2, fit.exponent, fit.exponent_error))
                rows.append((f"{tag}_max_over_min", 1, float(np.max(y) / np.min(y)), None))
        for j in range(len(w)):
            rows.append((f"fig5_{case}_lid_hits_per_base_hit_W{w[j]:.4g}", None, lid[j], None))
    full = load(directory, "channel-full-3d")
    g1 = "fig5_g1"
    if full is not None and g1 in study.points():
        for run in full.runs(full.points()[0]):
            vp = full.table.number(run, "drivers.vibrating_box.peak_velocity")
            ref = min(study.runs(g1), key=lambda r: abs(
                study.table.number(r, "drivers.vibrating_box.peak_velocity") - vp))
            for definition in full.definitions():
                rows.append((f"fig5_full_over_slice_W{vp * vp:.4g}_{definition}", 1,
                             *ratio(*full.tbar(run, definition), *study.tbar(ref, definition))))
    return rows


def rows(directory):
    return (ct_scan_rows(directory) + table1_window_rows(directory) +
            profile_peak_rows(directory) + fig5_rows(directory))
