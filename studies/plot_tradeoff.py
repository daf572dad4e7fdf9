#!/usr/bin/python3
"""Plot the speed-versus-accuracy analysis of a study (`gran tradeoff`, or a study with `tradeoff:`).

Usage:
    /usr/bin/python3 studies/plot_tradeoff.py STUDY.study.h5 [-o OUT.png]

Reads the /tradeoff group of the merged study file (docs/studies.md, "Trade-off"). One panel per
compared quantity and one for the worst of them: x is the run's cost (CPU seconds), y the error to
expect at that setting, |deviation from the reference| + its one-standard-error uncertainty
(relative). Markers are coloured by knob; the open circle is the reference; the step line is the
Pareto front (no other setting is both cheaper and more accurate). Each point is labelled with its
knob level. The path of the written PNG is printed; exit status 1 with a message on stderr when the
file has no /tradeoff group.
"""

import argparse
import math
import sys
from pathlib import Path

import numpy as np

import gran
from gran.style import DPI, plt


def short(q):
    parts = q.replace("observables.", "").split("/")
    return "/".join(parts[-3:]) if len(parts) > 3 else "/".join(parts)


def panel(ax, t, acc, pareto, title):
    knobs = list(dict.fromkeys(t["knobs"]))
    colours = {k: plt.cm.tab10(i % 10) for i, k in enumerate(knobs)}
    cost = np.asarray(t["cost"], float)
    acc = np.asarray(acc, float)
    floor = np.nanmin(acc[acc > 0]) / 3 if np.any(acc > 0) else 1e-4
    y = np.where(acc > 0, acc, floor)
    for k in knobs:
        sel = np.array([kk == k for kk in t["knobs"]])
        ax.scatter(cost[sel], 100 * y[sel], color=colours[k], label=k, s=28, zorder=3)
    ref = np.asarray(t["reference"], bool)
    ax.scatter(cost[ref], 100 * y[ref], facecolors="none", edgecolors="k", s=110, zorder=4,
               label="reference run")
    front = np.where(np.asarray(pareto, bool) & np.isfinite(cost) & np.isfinite(y))[0]
    front = front[np.argsort(cost[front])]
    if len(front):
        ax.step(cost[front], 100 * y[front], where="post", color="k", lw=1, ls="--", zorder=2,
                label="Pareto front")
    for i in range(len(cost)):
        if math.isfinite(cost[i]) and math.isfinite(y[i]):
            text = "reference" if ref[i] else t["levels"][i]
            ax.annotate(text, (cost[i], 100 * y[i]), fontsize=6, xytext=(3, 2),
                        textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cost [CPU s]")
    ax.set_ylabel("|deviation| + 1 sigma [%]")
    ax.set_title(title, fontsize=8)
    ax.grid(True, which="both", alpha=0.3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study")
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    try:
        with gran.Study.open(a.study) as study:
            t = study.tradeoff()
    except (OSError, KeyError) as e:
        print(f"plot_tradeoff: {e}", file=sys.stderr)
        return 1
    panels = [(p["accuracy"], p["pareto"], f"{short(p['name'])}\nreference: {p['kind']} = {p['reference']:.4g}")
              for p in t["panels"]]
    panels.append((t["worst"], t["pareto"], "worst quantity"))
    n = len(panels)
    cols = min(3, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.6 * cols, 3.8 * rows), squeeze=False)
    for ax, (acc, par, title) in zip(axes.flat, panels):
        panel(ax, t, acc, par, title)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=6, loc="best")
    fig.suptitle(f"speed versus accuracy: {Path(str(t['study'])).name}", fontsize=10)
    fig.tight_layout()
    out = a.output or str(Path(a.study).with_suffix("")).removesuffix(".study") + ".tradeoff.png"
    fig.savefig(out, dpi=DPI)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
