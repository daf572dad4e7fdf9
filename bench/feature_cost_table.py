#!/usr/bin/python3
"""Markdown tables of results/feature_cost.csv (written by gran_bench_features --csv) for
docs/performance.md: one row per feature, one column per geometry, each cell the median paired
CPU-time ratio to the baseline with [min-max] over the pairs.

    /usr/bin/python3 bench/feature_cost_table.py results/feature_cost.csv
"""
import csv
import sys


def cell(r):
    return f"{float(r['cost_ratio']):.2f} [{float(r['cost_ratio_min']):.2f}-{float(r['cost_ratio_max']):.2f}]"


def geometry(r):
    return f"{r['dimension']}D, phi {r['packing_fraction']}"


def table(rows, title_col):
    geos = []
    for r in rows:
        if geometry(r) not in geos:
            geos.append(geometry(r))
    feats = []
    for r in rows:
        if (r["feature"], r["baseline"]) not in feats:
            feats.append((r["feature"], r["baseline"]))
    by = {(r["feature"], geometry(r)): r for r in rows}
    out = [f"| {title_col} | baseline | " + " | ".join(geos) + " |",
           "|---|---|" + "---|" * len(geos)]
    for f, b in feats:
        cells = [cell(by[(f, g)]) if (f, g) in by else "—" for g in geos]
        out.append(f"| {f} | {b} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def main():
    with open(sys.argv[1] if len(sys.argv) > 1 else "results/feature_cost.csv") as f:
        rows = list(csv.DictReader(f))
    minimal = [r for r in rows if r["feature"] == "bare_vs_minimal_kernel"]
    ed = [r for r in rows if r["engine"] == "event_driven" and r not in minimal]
    dem = [r for r in rows if r["engine"] == "dem"]
    if minimal:
        print("| geometry | gran bare gas (coll/s) | gran / kernel CPU per collision |")
        print("|---|---|---|")
        for r in minimal:
            print(f"| {geometry(r)}, N {r['N']} | {float(r['rate']):.3g} | {cell(r)} |")
        print()
    if ed:
        print(table(ed, "event-driven feature"))
        print()
    if dem:
        print(table(dem, "DEM feature"))


if __name__ == "__main__":
    main()
