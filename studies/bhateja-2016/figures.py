#!/usr/bin/python3
"""Figures of Bhateja, Sharma & Singh, Phys. Fluids 28, 043301 (2016) from the study runs.

Usage: /usr/bin/python3 studies/bhateja-2016/figures.py [RESULTS_DIR]

Writes RESULTS_DIR/figures/*.png (one per paper figure or pair of figures, as named below); a
figure whose study has no results yet is skipped with a note. Filled circles: volume average
(the paper's Eq. (1)); open circles: particle average; open squares: plain average (about the
centre-of-mass velocity). Error bars: one standard error (gran's jackknife block errors). Every
plotted number comes from the result files; the only curves not measured are the paper's
Table III algebraic fits (dashed/dotted, labelled "paper").
"""
import sys
from pathlib import Path

import numpy as np

from analysis import (LIFT_OFF, W_PAPER_END, fig11_data, lid_alpha, lid_curve, load,
                      parameter_alphas, parameter_curves, paper_algebraic, peak, rest_height)
from fitting import MODELS, fit_model
from gran.style import label, plt, save

CASES = (("smooth", "C0"), ("rough", "C3"))
# marker, face (None: filled) and line per temperature definition
STYLE = {"volume": ("o", None, "-"), "particle": ("o", "none", ":"), "plain": ("s", "none", "--")}
WPROF = (5.58, 22.35, 50.3, 85.01)


def ebar(ax, x, y, e, color, definition, lbl, ls=None):
    """Error bars in the style of a temperature definition (ls "" for points only)."""
    marker, face, line = STYLE[definition]
    if np.all(np.isnan(np.asarray(y, float))):
        return
    ax.errorbar(x, y, yerr=e, fmt=marker + (line if ls is None else ls), color=color, mfc=face,
                ms=4, lw=0.9, capsize=2, label=lbl)


def fig2(sweeps, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    for ax, (dim, s) in zip(axes, sweeps.items()):
        for case, color in CASES:
            for d in s.definitions():
                w, y, e = s.curve(f"sweep{dim.lower()}_{case}", d)
                ebar(ax, w, y, e, color, d, f"{case}, {d}")
        wc = np.geomspace(1, 135, 200)
        ax.plot(wc, paper_algebraic(dim, wc), "k--", lw=1, label="paper Table III, rough")
        ax.axvspan(W_PAPER_END, 135, color="0.9", zorder=0)
        ax.set_xscale("log")
        label(ax, "W = V_p^2/(d g)", "T_z/(m V_p^2)", f"{dim} (grey: beyond the paper's sweep)")
    save(fig, out, "fig2", "Fig. 2: T_z/(m V_p^2) vs W, N = 4, A/d = 1")


def fig4(sweeps, out):
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    for col, (dim, s) in enumerate(sweeps.items()):
        for row, (comp, name) in enumerate((("T_x", "T_x"), ("T", "T = sum T_a / d_f"))):
            ax = axes[row, col]
            for case, color in CASES:
                for d in s.definitions():
                    w, y, e = s.curve(f"sweep{dim.lower()}_{case}", d, component=comp)
                    ebar(ax, w, y, e, color, d, f"{case}, {d}")
                w, y, _ = s.curve(f"sweep{dim.lower()}_{case}", "volume")
                ax.plot(w, y, color=color, lw=0.6, alpha=0.5, label=f"{case}: T_z (volume)")
            ax.set_xscale("log")
            label(ax, "W", f"{name}/(m V_p^2)", f"{dim}: {name}")
    save(fig, out, "fig4", "Fig. 4: horizontal and total temperature against W")


def fig6(directory, out):
    study = load(directory, "lid-g0")
    if study is None:
        return
    defs = study.definitions()
    fig, axes = plt.subplots(1, len(defs), figsize=(5.5 * len(defs), 4.3), squeeze=False)
    for ax, d in zip(axes[0], defs):
        for k, point in enumerate(study.points()):
            vp, t, _ = lid_curve(study, point, d)
            a, ae, lp = lid_alpha(study, point, d)
            ax.plot(vp, np.exp(lp) * vp**a, color=f"C{k}", lw=0.7)
            ebar(ax, vp, t[:, 0], t[:, 1], f"C{k}", d, f"{point}: alpha = {a:.3f}({ae * 1000:.0f})",
                 ls="")
        ax.set_xscale("log")
        ax.set_yscale("log")
        label(ax, "V_p [scene units]", "T_z [scene units]", f"{d} average", fontsize=7)
    save(fig, out, "fig6", "Fig. 6: g = 0, lid 10 d above the base: T_z ~ V_p^alpha (paper: 2)")


def fig7(directory, sweeps, out):
    fig, ax = plt.subplots(figsize=(6, 4.3))
    for (dim, s), color in zip(sweeps.items(), ("C2", "C3")):
        rest = rest_height(directory, dim, "rough")
        if rest is None:
            continue
        runs = s.runs(f"sweep{dim.lower()}_rough")
        runs = [r for r in runs if s.w(r) > LIFT_OFF]
        w = np.array([s.w(r) for r in runs])
        h = np.array([s.get(r, "observables.barycentric_height.h_cm") for r in runs])
        dh, dhe = h[:, 0] - rest[0], np.hypot(h[:, 1], rest[1])
        for d in s.definitions():
            t = np.array([s.temperature(r, d) for r in runs])
            v = t[:, 0] / dh
            e = np.abs(v) * np.hypot(t[:, 1] / t[:, 0], dhe / dh)
            ebar(ax, w, v, e, color, d, f"{dim} rough, {d}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    label(ax, "W", "Tbar_z / Delta hbar_cm = T_z/(m g Delta h_cm)",
          "Delta h_cm = h_cm - h_cm(rest), Delta hbar_cm = Delta h_cm g / V_p^2")
    save(fig, out, "fig7", "Fig. 7: T_z over the barycentric rise")


def fig8(sweeps, out):
    defs = sweeps["3D"].definitions()
    fig, axes = plt.subplots(len(defs), 2, figsize=(11, 4 * len(defs)), squeeze=False)
    for row, d in enumerate(defs):
        for (dim, s), color in zip(sweeps.items(), ("C2", "C3")):
            w, y, e = s.curve(f"sweep{dim.lower()}_rough", d)
            wf = peak(w, y)[0]
            m = (w >= wf) & (w <= W_PAPER_END)
            wc = np.geomspace(wf, 135, 200)
            for ax in axes[row]:
                ebar(ax, w[w >= wf], y[w >= wf], e[w >= wf], color, d, f"{dim} rough", ls="")
                for form, ls in (("algebraic", "-"), ("exponential", "--")):
                    p = fit_model(form, w[m], y[m], e[m])["p"]
                    ax.plot(wc, MODELS[form][0](wc, p), ls, color=color, lw=1,
                            label=f"{form}: a={p[0]:.3g} b={p[1]:.3g} c={p[2]:.3g}")
                ax.plot(wc, paper_algebraic(dim, wc), ":", color="k", lw=1.2,
                        label=f"paper algebraic {dim}")
        axes[row, 1].set_xscale("log")
        axes[row, 1].set_yscale("log")
        for ax, scale in zip(axes[row], ("linear", "log")):
            label(ax, "W", "T_z/(m V_p^2)", f"{d} average, {scale}; fits over W_f <= W <= 89.4",
                  fontsize=6)
    save(fig, out, "fig8", "Fig. 8 / Table III: fits after the peak (rough systems)")


PARAM_PANELS = (("(a) k_n", ("par2d_kn2e4", "par2d_canonical", "par2d_kn2e6"),
                 ("k_n = 2e4", "k_n = 2e5", "k_n = 2e6")),
                ("(b) e_p = e_w", ("par2d_e0.7", "par2d_e0.8", "par2d_canonical", "par2d_e0.95"),
                 ("0.7", "0.8", "0.9", "0.95")),
                ("(c) mu_p", ("par2d_mu0.1", "par2d_canonical", "par2d_mu0.8"),
                 ("0.1", "0.4", "0.8")),
                ("(d) N", ("par2d_N2", "par2d_N3", "par2d_canonical", "par2d_N6", "par2d_N8"),
                 ("2", "3", "4", "6", "8")))


def fig9_10(curves, plain, out):
    if not curves:
        return
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    for ax, (title, points, names) in zip(axes.flat, PARAM_PANELS):
        for k, (p, n) in enumerate(zip(points, names)):
            if p in curves:
                w, _, y, e, _ = curves[p]
                ebar(ax, w, y, e, f"C{k}", "volume", n)
        ax.set_xscale("log")
        label(ax, "W", "T_z/(m V_p^2) (volume)", f"2D rough, {title}")
    save(fig, out, "fig9", "Fig. 9: one parameter at a time (2D rough canonical: k_n 2e5, e 0.9, "
         "mu 0.4, N 4)")
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for d, c in (("volume", curves), ("plain", plain)):
        alphas = parameter_alphas(c)
        for ax, (title, points, names) in zip(axes, PARAM_PANELS[1:]):
            x = [float(n) for p, n in zip(points, names) if p in alphas]
            if not x:
                continue
            a = np.array([alphas[p][2:4] for p in points if p in alphas])
            marker, face, line = STYLE[d]
            ax.errorbar(x, a[:, 0], yerr=a[:, 1], fmt=marker + line, mfc=face, capsize=2, label=d)
            for xi, p in zip(x, [p for p in points if p in alphas]):
                ax.annotate(f"[{alphas[p][0]:.3g}, {alphas[p][1]:.3g}]", (xi, alphas[p][2]),
                            fontsize=6, textcoords="offset points", xytext=(2, 4))
            label(ax, title.split(") ")[1], "alpha over [W_f, W_2]", title)
    save(fig, out, "fig10", "Fig. 10: alpha of T_z ~ V_p^alpha over [W_f, W_2] (annotated; W_2: "
         "Tbar within 10% of its value at W = 135)")


def fig11(directory, out):
    data = fig11_data(directory)
    if data is None:
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    for d, t in data.items():
        ws = sorted({w for _, w in t})
        for k, w in enumerate(ws):
            a = sorted(x for x, ww in t if ww == w)
            v = np.array([t[(x, w)] for x in a])
            ebar(axes[0], a, v[:, 0], v[:, 1], f"C{k}", d, f"W = {w}, {d}")
        v = np.array([t[(1.0, w)] for w in ws])
        ebar(axes[1], ws, v[:, 0], v[:, 1], "k", d, f"A/d = 1, {d}")
    label(axes[0], "A/d", "T_z/(m g d)", "W fixed, A/d varied")
    label(axes[1], "W", "T_z/(m g d)", "A/d = 1, W varied")
    save(fig, out, "fig11", "Fig. 11: rough 2D, amplitude at fixed W")


def profile_panel(ax, p, color, lbl, key="T", scale=1.0):
    """One profile over the bed slabs: local T (filled circles), plain T (key "T_plain": open
    squares, dashed) or phi."""
    bed = p["bed"]
    if np.all(np.isnan(p[key][bed])):
        return
    marker, face, line = STYLE["plain" if key == "T_plain" else "volume"]
    ax.errorbar(p["z"][bed], p[key][bed] / scale, yerr=p[key + "_error"][bed] / scale,
                fmt=marker + line, mfc=face, ms=3, lw=0.9, capsize=1.5, color=color, label=lbl)


def fig12_13(directory, sweeps, out):
    study = load(directory, "profiles-3d")
    if study is None:
        return
    s3 = sweeps["3D"]
    fig, axes = plt.subplots(2, 5, figsize=(20, 8))
    for row, (key, name) in enumerate((("T", "local"), ("T_plain", "plain"))):
        for ax, w in zip(axes[row], (5.58, 22.35, 50.3, 68.46, 85.01)):
            for k, point in enumerate(study.points()):
                try:
                    profile_panel(ax, study.profile(study.at(point, w)), f"C{k}",
                                  point.removeprefix("prof3d_"), key=key)
                except KeyError:
                    pass
            if w > 60 and s3 is not None:  # Fig. 13: only the N = 4 sweep has these W
                profile_panel(ax, s3.profile(s3.at("sweep3d_smooth", w)), "C0", "N4 (sweep-3d)",
                              key=key)
            if w == 22.35:
                ax.axvspan(7, 10, color="0.9", zorder=0, label="paper: hottest 7-10 d")
            label(ax, "z/d (above the base's mean position)", f"T_z(z) [m g d], {name}",
                  f"W = {w}, {name}")
    save(fig, out, "fig12-13", "Figs. 12-13: T_z(z), 3D smooth, several N (bed slabs only); top: "
         "about the slab-and-phase mean, bottom: about the centre-of-mass velocity")


def fig14_15(sweeps, out):
    s3 = sweeps["3D"]
    fig, axes = plt.subplots(3, 2, figsize=(11, 12))
    for col, (case, _) in enumerate(CASES):
        for k, w in enumerate(WPROF):
            p = s3.profile(s3.at(f"sweep3d_{case}", w))
            profile_panel(axes[0, col], p, f"C{k}", f"W = {w}")
            profile_panel(axes[1, col], p, f"C{k}", f"W = {w}", key="T_plain")
            profile_panel(axes[2, col], p, f"C{k}", f"W = {w}", key="phi")
        label(axes[0, col], "z/d", "T_z(z) [m g d]", f"3D {case}: local temperature")
        label(axes[1, col], "z/d", "T_z(z) [m g d]",
              f"3D {case}: plain temperature (about the centre-of-mass velocity)")
        label(axes[2, col], "z/d", "phi(z)", f"3D {case}: volume fraction")
    save(fig, out, "fig14-15", "Figs. 14-15: T_z(z) (local and plain) and phi(z), 3D, N = 4")


def fig16(sweeps, out):
    stations = (1.5, 3.5, 5.5, 8.5, 12.5)
    fig, axes = plt.subplots(2, 4, figsize=(20, 8))
    for row, (dim, s) in enumerate(sweeps.items()):
        for col, ((case, _), (key, d)) in enumerate(
                (c, k) for c in CASES for k in (("T", "volume"), ("T_plain", "plain"))):
            ax = axes[row, col]
            runs = [r for r in s.runs(f"sweep{dim.lower()}_{case}") if s.w(r) > LIFT_OFF]
            profs = [s.profile(r) for r in runs]
            w = np.array([p["W"] for p in profs])
            for k, z in enumerate(stations):
                v = []
                for p in profs:
                    j = int(np.argmin(np.abs(p["z"] - z)))
                    ok = p["bed"][j]
                    v.append((p[key][j] / p["Vp"] ** 2, p[key + "_error"][j] / p["Vp"] ** 2)
                             if ok else (np.nan, np.nan))
                v = np.array(v)
                ebar(ax, w, v[:, 0], v[:, 1], f"C{k}", d, f"z = {z} d")
            _, y, e = s.curve(f"sweep{dim.lower()}_{case}", d)
            ax.plot(w, y[-len(w):], "k-", lw=1.5, label=f"bulk ({d})")
            ax.set_xscale("log")
            name = "local" if key == "T" else "plain"
            label(ax, "W", "T_z(z)/(m V_p^2)", f"{dim} {case}, {name}", fontsize=7)
    save(fig, out, "fig16", "Fig. 16: scaled T_z at fixed heights against W (local: about the "
         "slab-and-phase mean; plain: about the centre-of-mass velocity)")


def phi_profiles(sweeps, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    for ax, (dim, s) in zip(axes, sweeps.items()):
        for case, color in CASES:
            w, y, _ = s.curve(f"sweep{dim.lower()}_{case}", "volume")
            wf = peak(w, y)[0]
            for wv, ls in ((wf, "-"), (22.35, "--"), (85.01, ":")):
                p = s.profile(s.at(f"sweep{dim.lower()}_{case}", wv))
                bed = p["bed"]
                ax.errorbar(p["z"][bed], p["phi"][bed], yerr=p["phi_error"][bed], fmt=ls,
                            color=color, lw=1, label=f"{case}, W = {wv:.4g}" +
                            (" (W_f)" if wv == wf else ""))
        ax.axhline(0.2, color="k", lw=0.6, ls="-.", label="0.2 (paper: largest mean at W_f)")
        label(ax, "z/d", "phi(z)", f"{dim}")
    save(fig, out, "phi-profiles", "Volume (2D: area) fraction profiles, N = 4")


def engines(directory, out):
    study = load(directory, "engines-2d")
    if study is None:
        return
    fig, ax = plt.subplots(figsize=(6, 4.3))
    for k, ref in enumerate(study.runs("engines_event_driven")):
        wv = study.w(ref)
        for d in study.definitions():
            kn, v = [], []
            for point in study.points():
                if point.startswith("engines_dem_kn"):
                    r = study.at(point, wv)
                    kn.append(study.table.number(r, "interactions.stiffness"))
                    a, ea = study.tbar(r, d)
                    b, eb = study.tbar(ref, d)
                    v.append((a / b, a / b * np.hypot(ea / a, eb / b)))
            v = np.array(v)
            o = np.argsort(kn)
            ebar(ax, np.array(kn)[o], v[o, 0], v[o, 1], f"C{k}", d, f"W = {wv:.3g}, {d}")
    ax.axhline(1, color="k", lw=0.6)
    ax.set_xscale("log")
    label(ax, "k_n [m g / d]", "T_z(DEM) / T_z(event-driven)", "smooth 2D canonical bed")
    save(fig, out, "engines", "Both engines: DEM over event-driven T_z")


def fig5(directory, out):
    """Fig. 5: Tbar_z of the horizontally shaken channel against W, with and without gravity, and
    the lid hits per base hit (diagnostics.fig5_rows)."""
    study = load(directory, "fig5")
    if study is None:
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    for point, color in (("fig5_g1", "C0"), ("fig5_g0", "C2")):
        if point not in study.points():
            continue
        runs = study.runs(point)
        vp = np.array([study.table.number(r, "drivers.vibrating_box.peak_velocity") for r in runs])
        for d in study.definitions():
            ve = np.array([study.tbar(r, d) for r in runs])
            ebar(axes[0], vp ** 2, ve[:, 0], ve[:, 1], color, d,
                 f"{'g' if point.endswith('g1') else 'g = 0'}, {d}")
        lid = [study.table.number(r, "drivers.vibrating_box.hits_z_upper") /
               max(study.table.number(r, "drivers.vibrating_box.hits_z_lower"), 1) for r in runs]
        axes[1].plot(vp ** 2, lid, "o-", color=color, label=point)
    axes[0].set_xscale("log")
    label(axes[0], "W = V_p^2/(d g) (nominal g for g = 0)", "T_z/(m V_p^2)", "Tbar_z")
    axes[1].set_xscale("log")
    axes[1].set_yscale("log")
    label(axes[1], "W", "lid hits / base hits", "grains reaching the lid")
    save(fig, out, "fig5", "Fig. 5: channel 43 d x 10 d shaken along x, A = 10 d, e = 0.3, smooth")


def ct_scan(directory, out):
    """Tbar_z of the rough 3D bed against W for c_t / c_n = 0 ... 2, one panel per temperature
    definition, with the paper's algebraic Table III curve (and half of it: the x2 reading)."""
    from diagnostics import CT_POINTS
    studies = {n: load(directory, n) for n in ("ct-scan-3d", "sweep-3d")}
    if any(s is None for s in studies.values()):
        return
    defs = studies["sweep-3d"].definitions()
    fig, axes = plt.subplots(1, len(defs), figsize=(5.5 * len(defs), 4.3), squeeze=False)
    wc = np.geomspace(1, 135, 200)
    for ax, d in zip(axes[0], defs):
        for k, (ct, name, point) in enumerate(CT_POINTS):
            w, y, e = studies[name].curve(point, d)
            ebar(ax, w, y, e, f"C{k}", d, f"c_t = {ct} c_n")
        ax.plot(wc, paper_algebraic("3D", wc), "k--", lw=1, label="paper Table III")
        ax.plot(wc, paper_algebraic("3D", wc) / 2, "k:", lw=1, label="paper / 2")
        ax.set_xscale("log")
        label(ax, "W", "T_z/(m V_p^2)", f"3D rough, {d}")
    save(fig, out, "ct-scan", "Table III and Fig. 2 against the tangential damping c_t (3D rough)")


def profile_peak(directory, out):
    """Figs. 12-14 at W = 22.35 and 85.01: local T(z), plain T(z) and the density-weighted
    n(z) T(z) / N, each over its maximum (diagnostics.profile_peak_rows)."""
    from diagnostics import weighted_profile
    study = load(directory, "profiles-3d")
    s3 = load(directory, "sweep-3d")
    if study is None or s3 is None:
        return
    cases = (("N = 4, W = 22.35", study, "prof3d_N4", 22.35),
             ("N = 8, W = 22.35", study, "prof3d_N8", 22.35),
             ("N = 4, W = 85.01", s3, "sweep3d_smooth", 85.01))
    fig, axes = plt.subplots(1, len(cases), figsize=(16, 4.3))
    for ax, (title, st, point, w) in zip(axes, cases):
        p = st.profile(st.at(point, w))
        seen = p["grains"] > 0
        for key, values, style in (("local T", p["T"], "o-"), ("plain T", p["T_plain"], "s--"),
                                   ("instantaneous T", p["T_instant"], "d-"),
                                   ("n T / N", weighted_profile(p), "^-")):
            v = np.where(seen, values, np.nan)
            if np.all(np.isnan(v)):
                continue
            ax.plot(p["z"][seen], v[seen] / np.nanmax(v), style, ms=3, label=key)
        ax.axvspan(7, 10, color="0.9", zorder=0, label="paper: hottest 7-10 d")
        label(ax, "z/d", "profile / its maximum", f"3D smooth, {title}")
    save(fig, out, "profile-peak", "Where the profiles peak: T(z) against n(z) T(z) / N")


def main():
    directory = Path(sys.argv[1] if len(sys.argv) > 1 else "results/bhateja-2016")
    out = directory / "figures"
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("*.png"):  # rewritten from scratch: no figure of an earlier result stays
        old.unlink()
    sweeps = {"2D": load(directory, "sweep-2d"), "3D": load(directory, "sweep-3d")}
    if all(s is not None for s in sweeps.values()):
        fig2(sweeps, out)
        fig4(sweeps, out)
        fig7(directory, sweeps, out)
        fig8(sweeps, out)
        fig14_15(sweeps, out)
        fig16(sweeps, out)
        phi_profiles(sweeps, out)
        fig12_13(directory, sweeps, out)
    fig6(directory, out)
    fig9_10(parameter_curves(directory, sweeps), parameter_curves(directory, sweeps, "plain"),
            out)
    fig11(directory, out)
    engines(directory, out)
    fig5(directory, out)
    ct_scan(directory, out)
    profile_peak(directory, out)
    print(f"{out}: {', '.join(sorted(p.stem for p in out.glob('*.png')))}")


if __name__ == "__main__":
    main()
