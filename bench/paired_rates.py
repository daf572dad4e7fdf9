#!/usr/bin/python3
"""Per-case rate ratios of two builds from alternating benchmark runs (docs/performance.md).

    paired_rates.py {bench,dem,features} NEW.txt BASE.txt

NEW.txt and BASE.txt hold the concatenated output of repeated runs of one benchmark program
(gran_bench, gran_bench_dem or gran_bench_features), as written by
`farm-bench --vs "sh -c 'exec BASE ... >>BASE.txt'" -- sh -c 'exec NEW ... >>NEW.txt'`, which
alternates the two. Run k of one file is paired with run k of the other; the first run of each (the
warm-up) is dropped. For every case (gran_bench: case name; gran_bench_dem: N; features: geometry
and feature) prints the median, min and max over the pairs of rate_new / rate_base (above 1: new
is faster).
"""
import statistics
import sys

# program -> (start of the line that begins a run, number of key columns, column of the rate);
# gran_bench_dem's runs begin with its table header, whose first word is "N".
FORMATS = {"bench": ("gran_bench:", 1, 4), "dem": ("N ", 1, 3),
           "features": ("gran_bench_features", 2, 3)}


def runs(path, fmt):
    start, nkey, col = FORMATS[fmt]
    out, cur = [], None
    for line in open(path):
        p = line.split()
        if not p:
            continue
        header = line.lstrip().startswith(start)
        if header:
            if cur:
                out.append(cur)
            cur = {}
            continue
        if cur is None or len(p) <= col:
            continue
        try:
            cur[" ".join(p[:nkey])] = float(p[col])
        except ValueError:
            pass
    if cur:
        out.append(cur)
    return out[1:]


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in FORMATS:
        print(__doc__, file=sys.stderr)
        return 2
    fmt, new, base = sys.argv[1], runs(sys.argv[2], sys.argv[1]), runs(sys.argv[3], sys.argv[1])
    pairs = min(len(new), len(base))
    if pairs == 0:
        print("no complete pairs of runs", file=sys.stderr)
        return 1
    medians = []
    for key in new[0]:
        r = [new[i][key] / base[i][key] for i in range(pairs) if key in new[i] and key in base[i]]
        if not r:
            continue
        medians.append(statistics.median(r))
        print(f"{key:45s} new/base {medians[-1]:.3f} [{min(r):.3f}-{max(r):.3f}] pairs {len(r)}")
    print(f"{len(medians)} cases; median of the medians {statistics.median(medians):.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
