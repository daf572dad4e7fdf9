#!/usr/bin/python3
"""Figures 1-4, 6-9 and 13-17 of Barrat & Trizac, PRE 66, 051303 (2002) from the study runs.

Usage: /usr/bin/python3 studies/barrat-trizac-2002/figures.py [RESULTS_DIR]

Reads the runs of tables.yaml, monodisperse.yaml and mixture.yaml from RESULTS_DIR and writes
there: figN.png (one per paper figure, panels as in the paper), tables.png, comparison.csv
(rewritten from scratch: the rows of Tables I-II, then one row per number the paper states for
these figures) and claims.csv (the paper's qualitative statements about the figures, checked).
Error bars are one standard error (jackknife or block errors written by gran).
"""
import sys
from pathlib import Path

import numpy as np

import claims
import compare
from analysis import Results, cutoff_exponent, mono, second_moment, tail_exponent
from gran.style import errorbars, gaussian, label, plt, positive, save


# --- run names (see monodisperse.yaml and mixture.yaml) --------------------------------------

FIG7_RUNS = (  # (tag of the comparison rows, legend, run), all at phi0 = 0.015, beta = 0
    ("vibrating_a0.9", r"vibrating, $\alpha = 0.9$", mono(0.9, 0, 0.015)),
    ("vibrating_a0.8", r"vibrating, $\alpha = 0.8$", mono(0.8, 0, 0.015)),
    ("thermal_a0.9", r"thermal, $\alpha = 0.9$", mono(0.9, 0, 0.015, "thermal")),
)
WALLS_FIG9 = {"vibrating": mono(0.9, 0, 0.015), "thermal": mono(0.9, 0, 0.015, "thermal")}
ORDERINGS = {"987": r"$\alpha_{ij} = 0.9;0.8;0.7$", "789": r"$\alpha_{ij} = 0.7;0.8;0.9$"}
NUMBER_RATIOS = {"1to8": 1 / 8, "1to4": 1 / 4, "equimolar": 1.0, "4to1": 4.0, "8to1": 8.0}


def fig16_run(order, ratio):
    """Name of a Fig. 16 run (the equimolar one is the Table II run)."""
    return f"tableII_{order}_beta0" if ratio == "equimolar" else f"fig16_{order}_N1N2_{ratio}"


# --- plotting helpers ------------------------------------------------------------------------

def new_figure(ncols=1, width=5.2, height=4.2):
    """A figure with `ncols` panels side by side; returns (fig, list of axes)."""
    fig, axes = plt.subplots(1, ncols, figsize=(width * ncols, height), squeeze=False)
    return fig, list(axes[0])


Y_L = "$y/L$"


# --- Figures 1-4: one-component profiles and the equation of state ----------------------------

def fig1(res, outdir):
    """Fig. 1: packing-fraction profiles phi(y)/phi0, two inelasticities, two densities."""
    fig, (ax,) = new_figure()
    for alpha, marker in ((0.9, "o"), (0.8, "s")):
        errorbars(ax, res[mono(alpha, -1, 0.015)].density_profile("grain"), marker,
                  rf"$\phi_0 = 0.015$, $\alpha = {alpha}$")
        errorbars(ax, res[mono(alpha, -1, 0.04)].density_profile("grain"),
                  "-" if alpha == 0.9 else "--", rf"$\phi_0 = 0.04$, $\alpha = {alpha}$")
    label(ax, Y_L, r"$\phi(y)/\phi_0$")
    save(fig, outdir, "fig1", "Fig. 1: density profiles, N = 500, vibrating walls")
    return []


def fig2(res, outdir):
    """Fig. 2: density and total temperature profiles for four tangential restitutions."""
    fig, (a, b) = new_figure(2)
    for beta, fmt in ((-1, "o-"), (-0.8, "s-"), (-0.5, "^-"), (-0.2, "v-")):
        run = res[mono(0.9, beta, 0.015)]
        errorbars(a, run.density_profile("grain"), fmt, rf"$\beta = {beta}$")
        errorbars(b, run.profile("grain/T"), fmt, rf"$\beta = {beta}$")
    label(a, Y_L, r"$\phi(y)/\phi_0$", "(density: upward curves)")
    label(b, Y_L, r"$T(y)$  [$m v_0^2$]", "(temperature: downward curves)")
    save(fig, outdir, "fig2", r"Fig. 2: $\alpha = 0.9$, N = 500, $\phi_0 = 0.015$, vibrating walls")
    return []


def fig3(res, outdir):
    """Fig. 3: T_x, T_y and T profiles; inset: anisotropy A(y) = (T_y - T_x)/(2T)."""
    fig, (ax,) = new_figure(width=6)
    run = res[mono(0.9, -1, 0.04)]
    for key, fmt, name in (("T_y", "^", "$T_y$"), ("T", "o", "$T$"), ("T_x", "v", "$T_x$")):
        errorbars(ax, run.profile(f"grain/{key}"), fmt, name)
    label(ax, Y_L, r"temperature  [$m v_0^2$]", loc="upper left")
    inset = ax.inset_axes([0.35, 0.5, 0.38, 0.45])
    errorbars(inset, run.profile("mixture/anisotropy"), "k.")
    inset.set_xlabel(Y_L, fontsize=8)
    inset.set_ylabel(r"$A = (T_y - T_x)/(2T)$", fontsize=8)
    inset.tick_params(labelsize=7)
    save(fig, outdir, "fig3", r"Fig. 3: $\alpha = 0.9$, $\phi_0 = 0.04$, N = 500, vibrating walls")
    return []


def fig4(res, outdir):
    """Fig. 4: pressure from the equation of state (7), (a) with T, (b) with T_y (P_yy)."""
    fig, (a, b) = new_figure(2)
    for alpha, color in ((0.9, "C0"), (0.8, "C1"), (0.7, "C2")):
        run = res[mono(alpha, -1, 0.04)]
        for ax, suffix, temp in ((a, "", "T"), (b, "_yy", "T_y")):
            errorbars(ax, run.profile(f"eos/P_enskog{suffix}"), "o",
                      rf"$\alpha = {alpha}$, Enskog", color=color)
            errorbars(ax, run.profile(f"eos/P_ideal{suffix}"), "-",
                      rf"$\alpha = {alpha}$, ideal $\rho {temp}$", color=color)
        errorbars(b, run.profile("pressure/P_yy"), "k:", "measured $P_{yy}$ (virial)"
                  if alpha == 0.9 else None)
    for ax in (a, b):
        ax.set_yscale("log")
        ax.set_ylim(2.5e-3, 0.15)  # room for the legend below the curves
    label(a, Y_L, r"$P = \rho T\,[1 + (1+\alpha)\phi\chi]$", "(a) total temperature T",
          fontsize=7, ncol=3, loc="lower center")
    label(b, Y_L, r"$P_{yy} = \rho T_y\,[1 + (1+\alpha)\phi\chi]$",
          "(b) vertical temperature $T_y$", fontsize=7, ncol=2, loc="lower center")
    save(fig, outdir, "fig4",
         r"Fig. 4: equation of state, $\phi_0 = 0.04$, N = 500, vibrating walls")
    return []


# --- Figures 6-9: velocity distributions and effective restitution ---------------------------

def fig6(res, outdir):
    """Fig. 6: P(c_y) at several heights next to vibrating and thermal walls."""
    fig, axes = new_figure(2)
    rows = []
    for ax, wall in zip(axes, ("sawtooth", "thermal")):
        run = res[mono(0.9, 0, 0.04, wall)]
        for centre, fmt in ((0.025, "o-"), (0.1, "s-"), (0.25, "^-"), (0.5, "v-")):
            data = run.slab_pdf(centre, "y")
            errorbars(ax, data, fmt, f"$y/L$ = {centre}")
            if centre in (0.025, 0.5):
                # "By definition, <c_y^2> = 1 whatever the altitude y." (Fig. 6 caption)
                m, e = second_moment(data[0], data[1], data[2])
                rows.append((f"fig6_{'vibrating' if wall == 'sawtooth' else 'thermal'}"
                             f"_y{centre}_cy2", 1, m, e))
        gaussian(ax, fmt="k:")
        ax.set_xlim(-4, 6)
        label(ax, r"$c_y = v_y/\sqrt{T_y}$", r"$P(c_y)$",
              "vibrating (sawtooth) walls" if wall == "sawtooth" else "thermal walls")
    save(fig, outdir, "fig6", r"Fig. 6: $\phi_0 = 0.04$, N = 500, $\alpha = 0.9$, $\beta = 0$")
    return rows


def fig7(res, outdir):
    """Fig. 7(a): P(c_x) in the middle of the cell; (b) P of the angular velocities.

    Panel (b) (caption: "Probability distribution function of the angular velocities for the
    same parameters", i.e. phi0 = 0.015, N = 500, alpha = 0.9 and 0.8, beta = 0) is the whole
    cell, rescaled by the instantaneous sqrt(T_rot/I); the caption says neither where nor how
    it is rescaled. The paper gives no number for it, only "The angular velocity distributions,
    also displayed in Fig. 7, share a similar non-Gaussian character and the same dependence
    with the parameters": one row per run with its kurtosis against "> 3" (non-Gaussian, as
    P(c_x)); the dependence on the parameters goes to claims.csv."""
    fig, (a, b) = new_figure(2)
    rows = []
    for (_, name, run), fmt in zip(FIG7_RUNS, ("+", "*", "o")):
        kurt = res[run].slab_scalar(0.5, "x", "kurtosis")
        errorbars(a, positive(res[run].slab_pdf(0.5, "x")), fmt,
                  f"{name} (kurtosis {kurt:.2f})", mfc="none")
    for (tag, name, run), fmt in zip(FIG7_RUNS, ("+", "*", "o")):
        data, kurt, kerr = res[run].angular_pdf()
        errorbars(b, positive(data), fmt,
                  f"{name} (kurtosis {kurt:.3f} $\\pm$ {kerr:.3f})", mfc="none")
        rows.append((f"fig7b_{tag}_omega_kurtosis", "> 3", kurt, kerr))
    for ax in (a, b):
        gaussian(ax)
        ax.set_yscale("log")
        ax.set_xlim(-6, 6)
        ax.set_ylim(1e-5, 1)
    label(a, r"$c_x = v_x/\sqrt{T_x}$", r"$P(c_x)$", "(a) middle slab 0.475 < y/L < 0.525")
    label(b, r"$c_\omega = \omega/\sqrt{T_{rot}/I}$", r"$P(c_\omega)$",
          "(b) angular velocities, whole cell")
    save(fig, outdir, "fig7", r"Fig. 7: $\phi_0 = 0.015$, N = 500, $\beta = 0$")
    return rows


def fig8(res, outdir):
    """Fig. 8: distribution of alpha_1d; inset: its alpha_1d^-2 tail on log-log axes."""
    fig, (ax,) = new_figure(width=6)
    inset = ax.inset_axes([0.5, 0.42, 0.46, 0.54])
    rows = []
    for (tag, name, run), fmt in zip(FIG7_RUNS, ("-", "--", ":")):
        errorbars(ax, res[run].restitution(), fmt, name)
        k, e = tail_exponent(res[run])
        errorbars(inset, positive(res[run].restitution("alpha_1d_tail")), "." + fmt,
                  f"slope {k:.3f} ± {e:.3f}")
        # "Our study shows that P(alpha_1d) display a alpha_1d^-2 tail for alpha_1d > 1"
        rows.append((f"fig8_{tag}_tail_exponent", -2, k, e))
    x = np.array([1.0, 1000.0])
    inset.plot(x, 0.3 * x**-2.0, "k-", lw=0.8, label=r"$\alpha_{1d}^{-2}$")
    inset.set_xscale("log")
    inset.set_yscale("log")
    inset.tick_params(labelsize=7)
    inset.legend(fontsize=6)
    ax.set_xlim(-1, 4)
    label(ax, r"$\alpha_{1d} = -v'_{12,x}/v_{12,x}$", r"$P(\alpha_{1d})$",
          r"$\phi_0 = 0.015$, N = 500, $\beta = 0$", loc="upper left")
    save(fig, outdir, "fig8", "Fig. 8: effective one-dimensional restitution")
    return rows


def fig9(res, outdir):
    """Fig. 9: (a) P(alpha_1d | g_x = 1) for both walls; (b) against (alpha_1d g_x)^2."""
    fig, (a, b) = new_figure(2)
    rows = []
    for (wall, run), fmt in zip(WALLS_FIG9.items(), ("o", "s")):
        errorbars(a, positive(res[run].conditional(1.0)), fmt, f"{wall} walls", mfc="none")
        for g in (0.2, 0.5, 1.0):
            # "they ... show an exp[-(alpha_1d g_x)^2/R] decrease for the case of vibrating
            #  walls (closer to the experimental situation), and a broader form
            #  exp[-(alpha_1d g_x)/R'] for thermal walls"
            # The paper fits no exponent: 2 and 1 are the forms it reads off Fig. 9(b). q of a
            # form without prefactor depends on g_x and on the window (2.0 to 2.4 next to
            # vibrating walls, g_x = 0.5 at the top): README.md here and cutoff.py.
            q, e = cutoff_exponent(res[run].conditional(g), g)
            paper = 2 if wall == "vibrating" else 1
            rows.append((f"fig9_{wall}_g{g}_cutoff_exponent", paper, q, e))
    a.set_yscale("log")
    a.set_xlim(-1, 6)
    a.set_ylim(1e-5, 3)
    label(a, r"$\alpha_{1d}$", r"$P(\alpha_{1d}\,|\,g_x = 1)$", r"(a) $\alpha = 0.9$, $\beta = 0$")
    run = res[WALLS_FIG9["vibrating"]]
    for g in (0.2, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0):
        alpha, p, err = run.conditional(g)
        sel = (alpha > 0) & (err < 0.5 * p)  # bins with at least 4 collisions
        errorbars(b, ((alpha[sel] * g) ** 2, p[sel], err[sel]), ".-", f"$g_x$ = {g}", lw=0.8)
    b.set_yscale("log")
    b.set_xlim(0, 12)
    label(b, r"$(\alpha_{1d}\, g_x)^2$", r"$P(\alpha_{1d}\,|\,g_x)$",
          r"(b) vibrating walls, $\alpha = 0.9$, $\beta = 0$, $\phi_0 = 0.015$", ncol=2)
    save(fig, outdir, "fig9", r"Fig. 9: conditional distributions of $\alpha_{1d}$ "
         r"($g_x = |v_{12,x}|/\sqrt{2T}$)")
    return rows


# --- Figures 13-17: binary mixture ------------------------------------------------------------

def mixture_profiles(ax, run, fmt_heavy, fmt_light, suffix=""):
    """Density profiles rho_i(y)/rho_i,0 of both species of a mixture run."""
    errorbars(ax, run.density_profile("heavy"), fmt_heavy,
              r"$\rho_1/\rho_{1,0}$ (heavy)" + suffix)
    errorbars(ax, run.density_profile("light"), fmt_light,
              r"$\rho_2/\rho_{2,0}$ (light)" + suffix)


def fig13(res, outdir):
    """Fig. 13: temperatures, densities and gamma(y) for m1 = 3 m2 and 5 m2."""
    fig, axes = new_figure(2, height=4.6)
    for ax, m in zip(axes, (3, 5)):
        run = res[f"tableI_m{m}_beta0"]
        errorbars(ax, run.profile("heavy/T"), "v-", "$T_1$ (heavy)")
        errorbars(ax, run.profile("light/T"), "^-", "$T_2$ (light)")
        mixture_profiles(ax, run, "s-", "o-")
        errorbars(ax, run.gamma_profile(), "k--", r"$\gamma = T_2/T_1$")
        errorbars(ax, res[f"fig13_m{m}_N1N2_8to1"].gamma_profile(), "ko",
                  r"$\gamma$, $\rho_{1,0} = 8\rho_{2,0}$", mfc="none")
        label(ax, Y_L, r"$T_i$ [$m_2 v_0^2$], $\rho_i/\rho_{i,0}$, $\gamma$",
              f"({'a' if m == 3 else 'b'}) $m_1 = {m} m_2$", ncol=2)
    save(fig, outdir, "fig13", r"Fig. 13: $\phi_0 = 0.015$, $\rho_{1,0} = \rho_{2,0}$, "
         r"$\alpha_{ij} = 0.85$, $\beta = 0$, N = 500")
    return []


def fig14(res, outdir):
    """Fig. 14: density and gamma profiles for alpha_ij = 0.7;0.8;0.9 (lines) and reverse."""
    fig, (ax,) = new_figure(width=6, height=4.6)
    lines, symbols = res["tableII_789_beta0"], res["tableII_987_beta0"]
    mixture_profiles(ax, lines, "-", "-", ", 0.7;0.8;0.9")
    mixture_profiles(ax, symbols, "o", "s", ", 0.9;0.8;0.7")
    errorbars(ax, lines.gamma_profile(), "k--", r"$\gamma$, 0.7;0.8;0.9")
    errorbars(ax, symbols.gamma_profile(), "k*", r"$\gamma$, 0.9;0.8;0.7")
    label(ax, Y_L, r"$\rho_i/\rho_{i,0}$, $\gamma = T_2/T_1$", ncol=2)
    save(fig, outdir, "fig14", r"Fig. 14: $m_1 = 3m_2$, $\beta = 0$, $\rho_{1,0} = \rho_{2,0}$, "
         r"$\phi_0 = 0.015$, N = 500")
    return []


def fig15(res, outdir):
    """Fig. 15: gamma(y) (a) and gamma_x(y) (b) at phi0 = 0.015 and 0.04."""
    fig, axes = new_figure(2)
    runs = {r"$\phi_0 = 0.015$": "tableII_987_beta0", r"$\phi_0 = 0.04$": "fig15_987_phi0.04"}
    names = (r"$\gamma = T_2/T_1$", r"$\gamma_x = T_{2,x}/T_{1,x}$")
    for ax, comp, name in zip(axes, ("", "x"), names):
        for (lab, run), fmt in zip(runs.items(), ("o-", "s--")):
            errorbars(ax, res[run].gamma_profile(comp), fmt, lab)
        label(ax, Y_L, name, f"({'a' if not comp else 'b'})")
    save(fig, outdir, "fig15", r"Fig. 15: $m_1 = 3m_2$, $\alpha_{ij} = 0.9;0.8;0.7$, $\beta = 0$, "
         "N = 500")
    return []


def fig16(res, outdir):
    """Fig. 16: gamma(y) for several N1/N2 (both orderings) and gamma in the middle vs N1/N2."""
    fig, axes = new_figure(3, width=4.6)
    fmts = ("v-", "^-", "o-", "s-", "D-")
    for ax, (order, name) in zip(axes, ORDERINGS.items()):
        for (ratio, value), fmt in zip(NUMBER_RATIOS.items(), fmts):
            errorbars(ax, res[fig16_run(order, ratio)].gamma_profile(), fmt,
                      f"$N_1/N_2$ = {value:g}")
        label(ax, Y_L, r"$\gamma = T_2/T_1$", name)
    for (order, name), fmt in zip(ORDERINGS.items(), ("o-", "s--")):
        mid = np.array([res[fig16_run(order, r)].middle_gamma() for r in NUMBER_RATIOS])
        ratios = np.array(list(NUMBER_RATIOS.values()))
        errorbars(axes[2], (ratios, mid[:, 0], mid[:, 1]), fmt, name)
    axes[2].set_xscale("log")
    axes[2].set_xticks(list(NUMBER_RATIOS.values()), ["1/8", "1/4", "1", "4", "8"])
    axes[2].minorticks_off()
    label(axes[2], "$N_1/N_2$", r"$\gamma$ in the middle (0.4 < y/L < 0.6)")
    save(fig, outdir, "fig16", r"Fig. 16: number fraction, $N_1 + N_2 = 500$, $m_1 = 3m_2$, "
         r"$\beta = 0$, $\phi_0 = 0.015$")
    return []


def fig17(res, outdir):
    """Fig. 17: rescaled P_1(c_x), P_2(c_x) of both species in the middle of the cell."""
    fig, (ax,) = new_figure(width=6)
    run = res["tableII_987_beta0"]
    for species, fmt, name in (("heavy", "s", "$P_1$ (heavy)"), ("light", "o", "$P_2$ (light)")):
        kurt = run.slab_scalar(0.5, "x", "kurtosis", species)
        errorbars(ax, positive(run.slab_pdf(0.5, "x", species)), fmt,
                  f"{name}, kurtosis {kurt:.2f}", mfc="none")
    gaussian(ax)
    ax.set_yscale("log")
    ax.set_xlim(-6, 6)
    ax.set_ylim(1e-5, 1)
    label(ax, r"$c_{i,x} = v_{i,x}/\sqrt{T_{i,x}/m_i}$", r"$P_i(c_x)$",
          "middle slab 0.47 < y/L < 0.53")
    save(fig, outdir, "fig17", r"Fig. 17: $\phi_0 = 0.015$, N = 500, $\alpha_{ij} = 0.9;0.8;0.7$, "
         r"$m_1 = 3m_2$, $\beta = 0$")
    return []


FIGURES = (fig1, fig2, fig3, fig4, fig6, fig7, fig8, fig9, fig13, fig14, fig15, fig16, fig17)


def main():
    outdir = Path(sys.argv[1] if len(sys.argv) > 1 else "results/barrat-trizac-2002")
    res = Results(outdir)
    tables = compare.table_rows(res)
    compare.plot_tables(tables, outdir / "tables.png")
    rows = list(tables)
    for make in FIGURES:
        rows += make(res, outdir)
    compare.write_csv(rows, outdir / "comparison.csv")
    checked = claims.check_all(res)
    claims.write_csv(checked, outdir / "claims.csv")
    print(f"{len(FIGURES)} figures, tables.png; comparison.csv: {len(tables)} table rows + "
          f"{len(rows) - len(tables)} figure rows; claims.csv: "
          f"{sum(c['holds'] for c in checked)}/{len(checked)} statements hold")
    for q, p, m, e in rows[len(tables):]:
        print(f"  {q:45s} paper {p:>6}  measured {m:8.4f} +- {e:.4f}")


if __name__ == "__main__":
    main()
