#!/usr/bin/python3
"""Diagnostics of the Fig. 9 cut-off exponent and of Fig. 7(b) (runs of cutoff.yaml).

Usage: PYTHONPATH=python /usr/bin/python3 studies/barrat-trizac-2002/cutoff.py OUT
(OUT: the result folder of `gran study studies/barrat-trizac-2002/cutoff.yaml -o OUT`).

Prints, and writes to OUT/cutoff.csv and OUT/cutoff.png:
  1. q(g_x): the exponent of P(alpha_1d | g_x) ~ exp(-(alpha_1d g_x)^q / R) fitted exactly as the
     fig9_*_cutoff_exponent rows of comparison.csv (analysis.cutoff_exponent), for g_x = 0.2 to
     1.5, per seed and on the three seeds pooled;
  2. at g_x = 0.5: the same fit with the histogram rebinned, a lower count threshold, the g_x
     window five times narrower, and over sub-windows of u = alpha_1d g_x;
  3. on the pooled runs, chi^2 per degree of freedom of five forms of log P over the window of
     the comparison rows: q free; q = 2 (the paper's form, constant prefactor); q = 2 with a
     power-law prefactor u^k; q = 2 about a shifted centre, exp(-(u - delta)^2 / R); q = 1;
  4. Fig. 7(b): the kurtosis of the angular velocities over the whole cell and in slabs, from the
     2000 frames of fine_g_s1 (block jackknife errors).
"""
import sys
from pathlib import Path

import numpy as np

from analysis import Results, cutoff_exponent, stretched_exponent_fit
from gran import comparison
from gran.style import errorbars, label, plt, positive, save

GS = (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5)
SEEDS = (1, 2, 3)


def pooled(res, g):
    """P(alpha_1d | g_x) averaged over the three seeds: (alpha, P, error)."""
    runs = [res[f"fine_g_s{s}"].conditional(g) for s in SEEDS]
    p = np.mean([r[1] for r in runs], axis=0)
    return runs[0][0], p, np.sqrt(np.sum([r[2] ** 2 for r in runs], axis=0)) / len(runs)


def rebin(data, k):
    """Merge k neighbouring bins of a histogram density (alpha, P, error)."""
    a, p, e = data
    n = len(a) // k * k
    return (a[:n].reshape(-1, k).mean(1), p[:n].reshape(-1, k).mean(1),
            np.sqrt((e[:n].reshape(-1, k) ** 2).sum(1)) / k)


def window_q(data, g, ulo, uhi):
    """q fitted over ulo < alpha_1d g_x < uhi (alpha_1d > 1.5 / g_x as in the comparison rows)."""
    a, p, e = data
    sel = (a * g < uhi)
    return stretched_exponent_fit(a[sel], p[sel], e[sel], g=g, lo=max(ulo / g, 1.5 / g, 1.0))


def _wls(columns, y, w):
    """Weighted linear least squares: (coefficients, chi^2)."""
    x = np.column_stack(columns)
    coef, *_ = np.linalg.lstsq(x * w[:, None], y * w, rcond=None)
    r = (y - x @ coef) * w
    return coef, float(r @ r)


def forms(data, g):
    """chi^2/dof of the five forms over the comparison rows' window, and k, delta, q."""
    a, p, e = data
    sel = (a > max(1.5, 1.5 / g)) & (p > 0) & (e > 0) & (e < p / 4)
    u, ly, w = a[sel] * g, np.log(p[sel]), p[sel] / e[sel]
    n, one = int(sel.sum()), np.ones(int(sel.sum()))
    q, _ = stretched_exponent_fit(a, p, e, g=g, lo=max(1.5, 1.5 / g))
    out = {"n": n, "q": q}
    out["free_q"] = _wls([one, u**q], ly, w)[1] / (n - 3)
    out["q2"] = _wls([one, u**2], ly, w)[1] / (n - 2)
    coef, chi = _wls([one, np.log(u), u**2], ly, w)
    out["q2_prefactor"], out["k"] = chi / (n - 3), coef[1]
    coef, chi = _wls([one, u, u**2], ly, w)
    out["q2_shifted"], out["delta"] = chi / (n - 3), -coef[1] / (2 * coef[2])
    out["q1"] = _wls([one, u], ly, w)[1] / (n - 2)
    return out


def frame_kurtosis(run, slabs, blocks=20):
    """Kurtosis of the angular velocities in slabs (lo, hi) of y/L from the frames of a run,
    rescaled by the slab's time-averaged sqrt(T_rot/I), and over the whole cell rescaled frame by
    frame (as the angular_velocity_pdf observable): {slab: (kurtosis, error, samples)}."""
    r = run.result
    height = r.box_lengths[1]
    y = np.array([np.asarray(r.positions(k))[:, 1] / height for k in range(r.frames)])
    w = np.array([np.asarray(r.angular_velocities(k)).reshape(len(y[0]), -1)[:, 0]
                  for k in range(r.frames)])

    def kurt(c):
        parts = np.array_split(np.arange(len(c)), blocks)
        m2 = np.array([np.nanmean(c[i] ** 2) for i in parts])
        m4 = np.array([np.nanmean(c[i] ** 4) for i in parts])
        jk = np.array([np.delete(m4, j).mean() / np.delete(m2, j).mean() ** 2
                       for j in range(blocks)])
        k = np.nanmean(c**4) / np.nanmean(c**2) ** 2
        return float(k), float(np.sqrt((blocks - 1) / blocks * np.sum((jk - jk.mean()) ** 2)))

    out = {"whole cell": (*kurt(w / np.sqrt((w**2).mean(1))[:, None]), w.size)}
    for lo, hi in slabs:
        sel = (y > lo) & (y < hi)
        c = np.where(sel, w, np.nan)
        out[f"{lo} < y/L < {hi}"] = (*kurt(c / np.sqrt(np.nanmean(c**2))), int(sel.sum()))
    return out


def main():
    outdir = Path(sys.argv[1] if len(sys.argv) > 1 else "results/barrat-trizac-2002-cutoff")
    res = Results(outdir)
    rows = []

    print("1. q(g_x), fit of the comparison rows (alpha_1d, alpha_1d g_x > 1.5), vibrating walls")
    qg = {}
    for g in GS:
        per = [cutoff_exponent(res[f"fine_g_s{s}"].conditional(g), g) for s in SEEDS]
        qg[g] = cutoff_exponent(pooled(res, g), g)
        print(f"  g_x {g:.1f}: " + "  ".join(f"seed {s} {q:.3f}({e:.3f})"
                                              for s, (q, e) in zip(SEEDS, per))
              + f"  pooled {qg[g][0]:.3f}({qg[g][1]:.3f})")
        rows.append((f"q_g{g}_pooled", 2, *qg[g]))

    print("2. g_x = 0.5, seed 1: the same fit with other choices")
    base = res["fine_g_s1"].conditional(0.5)
    variants = {
        "as in comparison.csv": cutoff_exponent(base, 0.5),
        "bins x2": cutoff_exponent(rebin(base, 2), 0.5),
        "bins x4": cutoff_exponent(rebin(base, 4), 0.5),
        "bins with >= 4 counts": stretched_exponent_fit(*base, g=0.5, lo=3.0, min_counts=4),
        "g_x window 0.02 (not 0.1)": cutoff_exponent(res["narrow_g"].conditional(0.5), 0.5),
    }
    pool = pooled(res, 0.5)
    for lo, hi in ((1.5, 2.5), (2.0, 3.0), (2.5, 3.5)):
        variants[f"pooled, {lo} < u < {hi}"] = window_q(pool, 0.5, lo, hi)
    for name, (q, e) in variants.items():
        print(f"  {name:28s} q = {q:.3f}({e:.3f})")
        rows.append((f"q_g0.5_{name.replace(' ', '_')}", 2, q, e))

    print("3. chi^2/dof of the forms of log P over the same window (pooled seeds)")
    print("  g_x   n  free q (q)     q=2   q=2 u^k (k)     q=2 shifted (delta)   q=1")
    for g in (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0, 1.2):
        f = forms(pooled(res, g), g)
        print(f"  {g:.1f} {f['n']:4d}  {f['free_q']:.2f} ({f['q']:.2f})  {f['q2']:5.2f}  "
              f"{f['q2_prefactor']:.2f} ({f['k']:+.2f})   {f['q2_shifted']:.2f} ({f['delta']:.2f})"
              f"           {f['q1']:.2f}")
        for key in ("free_q", "q2", "q2_prefactor", "q2_shifted", "q1"):
            rows.append((f"chi2dof_g{g}_{key}", None, f[key], None))

    print("4. Fig. 7(b): kurtosis of the angular velocities (frames of fine_g_s1)")
    kurt = frame_kurtosis(res["fine_g_s1"], ((0.45, 0.55), (0.4, 0.6), (0.25, 0.75), (0.0, 0.1)))
    for name, (k, e, n) in kurt.items():
        print(f"  {name:20s} {k:.4f}({e:.4f})  ({n} samples)")
        rows.append((f"omega_kurtosis_{name.replace(' ', '_')}", "> 3", k, e))
    comparison.write(rows, outdir / "cutoff.csv", paper="{}", measured="{:.4f}", error="{:.4f}")

    fig, (a, b) = plt.subplots(1, 2, figsize=(10.4, 4.2))
    for s, fmt in zip(SEEDS, ("o", "s", "^")):
        q = np.array([cutoff_exponent(res[f"fine_g_s{s}"].conditional(g), g) for g in GS])
        errorbars(a, (np.array(GS) + 0.01 * (s - 2), q[:, 0], q[:, 1]), fmt, f"seed {s}",
                  mfc="none")
    errorbars(a, (np.array(GS), *np.array([qg[g] for g in GS]).T), "k-", "three seeds pooled")
    a.axhline(2, color="C3", ls="--", lw=1, label="paper: exp$[-(\\alpha_{1d} g_x)^2/R]$")
    a.set_ylim(1.5, 3.2)
    label(a, "$g_x$", "$q$ of exp$[-(\\alpha_{1d} g_x)^q/R]$",
          "(a) fitted where $\\alpha_{1d}$, $\\alpha_{1d} g_x > 1.5$")
    al, p, e = pool
    sel = (al > 0) & (p > 0)
    errorbars(b, positive(((al[sel] * 0.5) ** 2, p[sel], e[sel])), ".", "$g_x = 0.5$, pooled")
    fsel = (al > 3) & (p > 0) & (e < p / 4)
    u = al[fsel] * 0.5
    curves = []
    for q, fmt in ((2.0, "C3--"), (qg[0.5][0], "k-")):
        coef = np.polyfit(u**q, np.log(p[fsel]), 1, w=p[fsel] / e[fsel])
        uu = np.linspace(1.5, u.max(), 100)
        b.plot(uu**2, np.exp(np.polyval(coef, uu**q)), fmt, lw=1, label=f"fit, q = {q:.2f}")
        curves.append(np.polyval(coef, uu**q))
    ratio = np.exp(curves[0] - curves[1])  # q = 2 fit over the q = q(0.5) fit
    print(f"  (b) the q = 2 fit over the q = {qg[0.5][0]:.2f} fit: "
          f"{ratio[uu**2 < 10].min():.2f}-{ratio[uu**2 < 10].max():.2f} for (alpha g)^2 < 10, "
          f"{ratio[-1]:.2f} at (alpha g)^2 = {uu[-1]**2:.1f}")
    b.set_yscale("log")
    b.set_xlim(0, 16)
    b.set_ylim(1e-5, 1)
    label(b, "$(\\alpha_{1d} g_x)^2$", "$P(\\alpha_{1d} | g_x = 0.5)$",
          "(b) the paper's axes (Fig. 9b)")
    save(fig, outdir, "cutoff", "Fig. 9 cut-off exponent: vibrating walls, "
         "$\\alpha = 0.9$, $\\beta = 0$, $\\phi_0 = 0.015$")
    print(f"{outdir / 'cutoff.csv'}, {outdir / 'cutoff.png'}")


if __name__ == "__main__":
    main()
