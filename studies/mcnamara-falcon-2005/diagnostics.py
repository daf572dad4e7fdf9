#!/usr/bin/python3
"""Diagnostics of the three statements of McNamara & Falcon (2005) that figures.py does not
reproduce (issue 16, item 3; the verdicts are in README.md here).

Usage: /usr/bin/python3 studies/mcnamara-falcon-2005/diagnostics.py [RESULTS_DIR]

RESULTS_DIR must hold the runs of sweep.yaml, diag-fig2b.yaml, diag-fig3.yaml and diag-fig4d.yaml
(`gran study ... -o RESULTS_DIR` for each; README.md). Prints three tables and writes
RESULTS_DIR/diagnostics.csv (`quantity,value,error`, rewritten from scratch):

- Fig. 2b: the lid-pressure maximum in n, with gravity and r = r(v), per frequency: the largest P
  on the merged n grid (sweep + diag-fig2b), the largest P for n < 4 (the paper describes the
  n >= 4 resonance separately), and a sub-grid estimate (vertex of the parabola through that point
  and its neighbours) with a 16-84% range from redrawing every P within its error bar.
- Fig. 3: the fraction of disks in "the tight cluster" at n = 3, f = 30 Hz for several cluster
  definitions (Voronoi packing fraction per disk; largest connected cluster of disks whose gaps
  are below a fraction of d) over the seeds and the variants of diag-fig3.yaml.
- Fig. 4d: the largest log deviation of every fit of diag-fig4d.yaml (n = 3 ... 6, variants), read
  with natural logarithms (gran) and with decimal ones (the paper does not say which); and of
  diag-fig4d-walls.yaml and diag-fig4d-hexbed.yaml (two more readings, when they have run).
"""
import csv
import math
import sys
from pathlib import Path

import numpy as np

from analysis import QUANTITIES, Snapshot, Sweep, mean_and_error
from gran.studies import StudyFolder

LN10 = math.log(10)
TOLERANCE = 0.25  # the paper's |log X_observed - log X_fitted| >= 0.25 rule (Sec. III B)
GAPS = (0.1, 0.25, 0.5)  # largest-cluster links: centre distance < d (1 + gap)
VORONOI = (0.4, 0.5)  # Voronoi packing-fraction thresholds (figures.py uses 0.5)
FIG3_POINTS = ("r0.7", "r0.7_tc1e-8", "r0.7_tc1e-6", "r0.7_tc1e-5", "r0.7_late", "r0.95", "rv")
FIG4D_POINTS = ("g_rv", "g_rv_seed2", "g_rv_dt0.01", "g_rv_tc1e-6", "g_rv_tc1e-5", "g_rv_hot")
FIG4D_QUANTITIES = QUANTITIES + ("KE",)
RESONANCE_N = 4  # "For n >= 4 and for certain frequencies, a resonance appears in Fig. 2b"
PRESSURE = "observables.wall_pressure.upper.pressure"


# --- Fig. 2b ----------------------------------------------------------------------------------

def pressure_curve(tables, f):
    """P(n) with gravity and r = r(v) at frequency f over every table's g_rv runs: (n, P, error)."""
    points = {}
    for table in tables:
        for row in table.runs("g_rv"):
            if int(row["drivers.0.frequency"]) == f:
                p, e = table.value_and_error(row, PRESSURE)
                points[int(row["species.0.count"]) / 100] = (p, e)
    n = np.array(sorted(points))
    return n, np.array([points[k][0] for k in n]), np.array([points[k][1] for k in n])


def vertex(n, p, k):
    """n of the vertex of the parabola through points k-1, k, k+1 (n[k] at the ends)."""
    if k == 0 or k == len(n) - 1:
        return float(n[k])
    a, b, _ = np.polyfit(n[k - 1:k + 2], p[k - 1:k + 2], 2)
    return float(np.clip(-b / (2 * a), n[k - 1], n[k + 1])) if a < 0 else float(n[k])


def fig2b(directory, rows):
    tables = [StudyFolder(directory, "sweep").table, StudyFolder(directory, "diag-fig2b").table]
    rng = np.random.default_rng(1)
    print("Fig. 2b: n of the lid-pressure maximum (g, r = r(v))")
    print("   f   argmax(all n)  argmax(n<4)  vertex(n<4) [16%, 84%]")
    for f in range(10, 31, 2):
        n, p, e = pressure_curve(tables, f)
        main = n < RESONANCE_N
        k = int(np.argmax(p[main]))
        draws = []
        for _ in range(2000):
            q = rng.normal(p[main], e[main])
            draws.append(vertex(n[main], q, int(np.argmax(q))))
        lo, hi = np.percentile(draws, [16, 84])
        v = vertex(n[main], p[main], k)
        print(f"  {f:2d}   {n[np.argmax(p)]:5.2f}          {n[main][k]:5.2f}        {v:5.2f} "
              f"[{lo:.2f}, {hi:.2f}]")
        rows += [(f"fig2b_argmax_all_n_f{f}", n[np.argmax(p)], None),
                 (f"fig2b_argmax_n_below4_f{f}", n[main][k], None),
                 (f"fig2b_vertex_n_below4_f{f}", v, (hi - lo) / 2)]


# --- Fig. 3 -----------------------------------------------------------------------------------

def largest_cluster(positions, width, diameter, gap):
    """Fraction of the disks in the largest connected cluster, two disks linked when their
    centres are closer than d (1 + gap) (periodic in x); and the height of its highest centre."""
    dx = positions[:, None, 0] - positions[None, :, 0]
    dx -= width * np.round(dx / width)
    dy = positions[:, None, 1] - positions[None, :, 1]
    linked = dx**2 + dy**2 < (diameter * (1 + gap)) ** 2
    label = np.arange(len(positions))
    while True:  # label propagation: every disk takes the smallest label among its links
        new = np.minimum(np.where(linked, label[None, :], len(label)).min(axis=1), label)
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    biggest = np.argmax(np.bincount(label))
    return np.mean(label == biggest), positions[label == biggest, 1].max()


def fig3(directory, rows):
    study = StudyFolder(directory, "diag-fig3")
    print("\nFig. 3: % of the disks in the cluster (n = 3, g, f = 30 Hz; 20 frames per run, "
          "mean +- s.e. over all frames of all seeds; [largest frame])")
    head = [f"Voronoi>{t}" for t in VORONOI] + [f"largest, gaps<{g}d" for g in GAPS]
    print(f"  {'point':13s} seeds " + "".join(f"{h:>22s}" for h in head)
          + "   frames with a majority (gaps<0.25d)  cluster at the lid")
    for point in FIG3_POINTS:
        runs = [Snapshot(directory / f"{row['run']}.h5") for row in study.table.runs(point)]
        values = {h: [] for h in head}
        at_lid = []
        for s in runs:
            for k in range(s.frames):
                phi = s.local_packing_fraction(k)
                for t, h in zip(VORONOI, head):
                    values[h].append(np.mean(phi > t))
                for g, h in zip(GAPS, head[len(VORONOI):]):
                    frac, top = largest_cluster(s.positions(k), s.width, s.diameter, g)
                    values[h].append(frac)
                    if g == 0.25:
                        at_lid.append(top > s.height - 1.5 * s.diameter)
        cells = []
        for h in head:
            m, e = mean_and_error(values[h])
            cells.append(f"{100 * m:5.1f} +- {100 * e:3.1f} [{100 * max(values[h]):2.0f}]")
            rows.append((f"fig3_{point}_{h.replace(' ', '').replace(',', '_')}", m, e))
        majority = np.mean(np.array(values[head[len(VORONOI) + 1]]) > 0.5)
        rows.append((f"fig3_{point}_frames_majority_gaps0.25d", majority, None))
        rows.append((f"fig3_{point}_frames_cluster_at_lid", np.mean(at_lid), None))
        print(f"  {point:13s} {len(runs):5d} " + "".join(f"{c:>22s}" for c in cells)
              + f"   {100 * majority:5.0f}%{'':30s}{100 * np.mean(at_lid):4.0f}%")


# --- Fig. 4d ----------------------------------------------------------------------------------

def fig4d(directory, rows):
    study = StudyFolder(directory, "diag-fig4d")
    layers = sorted({int(r["species.0.count"]) for r in study.table.runs("g_rv")})
    print("\nFig. 4d: largest |ln X - ln X_fit| over f = 10 ... 30 Hz (g, r = r(v)); '*': fails "
          f"|ln| >= {TOLERANCE} (gran), '**': fails |log10| >= {TOLERANCE} too")
    print(f"  {'point':12s} {'X':3s}" + "".join(f"{'n=' + format(c / 100, 'g'):>9s}"
                                            for c in layers))
    for point in FIG4D_POINTS:
        for q in FIG4D_QUANTITIES:
            cells = []
            for c in layers:
                dev = study.fit(f"theta_{q}_{point}_count{c}").max_deviation
                mark = "**" if dev / LN10 >= TOLERANCE else "*" if dev >= TOLERANCE else ""
                cells.append(f"{dev:.3f}{mark:2s}")
                rows.append((f"fig4d_maxdev_{q}_{point}_n{c / 100:g}", dev, None))
            print(f"  {point:12s} {q:3s}" + "".join(f"{x:>9s}" for x in cells))


FIG4D_READINGS = (("diag-fig4d-walls", "g_rv_walls_r0.95"), ("diag-fig4d-hexbed", "g_rv_hexbed"))


def fig4d_readings(directory, rows):
    """The two readings of diag-fig4d-walls.yaml and diag-fig4d-hexbed.yaml (skipped with a note
    when they have not run): walls with constant restitution, the lid above a hexagonal bed."""
    for name, point in FIG4D_READINGS:
        try:
            study = StudyFolder(directory, name)
        except FileNotFoundError:
            print(f"\nskipped: {name} has not run in {directory}")
            continue
        layers = sorted({int(r["species.0.count"]) for r in study.table.runs(point)})
        print(f"  {point:18s}" + "".join(f"{'n=' + format(c / 100, 'g'):>9s}" for c in layers))
        for q in QUANTITIES:
            cells = []
            for c in layers:
                dev = study.fit(f"theta_{q}_{point}_count{c}").max_deviation
                cells.append(f"{dev:.3f}{'*' if dev >= TOLERANCE else ' '} ")
                rows.append((f"fig4d_maxdev_{q}_{point}_n{c / 100:g}", dev, None))
            print(f"  {q:18s}" + "".join(f"{x:>9s}" for x in cells))


def main():
    directory = Path(sys.argv[1] if len(sys.argv) > 1 else "results/mcnamara-falcon-2005")
    Sweep(directory)  # fails early, naming the missing study, when sweep.yaml has not run
    rows = []
    fig2b(directory, rows)
    fig3(directory, rows)
    fig4d(directory, rows)
    fig4d_readings(directory, rows)
    with open(directory / "diagnostics.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["quantity", "value", "error"])
        for q, v, e in rows:
            w.writerow([q, f"{v:.6g}", "" if e is None else f"{e:.3g}"])
    print(f"\n{directory / 'diagnostics.csv'}: {len(rows)} rows")


if __name__ == "__main__":
    main()
