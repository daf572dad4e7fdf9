#!/usr/bin/env bash
# gran's DEM benchmark against LIGGGHTS on the same vibrated bed (bench/liggghts/README.md).
#
#   bench/liggghts/compare.sh [RUNS] [SIZES]        e.g. bench/liggghts/compare.sh 5 100,1600,10000
#
# Environment: GRAN_BENCH_DEM (default build/gran_bench_dem), LIGGGHTS (default liggghts),
# WARMUP_PERIODS (default 2), W (default 9; 0: the bed settled on a static floor),
# PSTEPS_SMALL (default 2e7, N < 10^4), PSTEPS_LARGE (default 5e7),
# OUT (default a new directory under /tmp: every run's full output is kept there).
# PEER_HUGE_PAGES (default 1: both codes with glibc.malloc.hugetlb=1, bench/same_pages.sh; 0: neither).
#
# Runs gran and LIGGGHTS alternately, RUNS times each per size, serially (one process each,
# OMP_NUM_THREADS=1), with equal warm-up and equal timed particle-steps, and reads each code's own
# timing of its timed loop:
#   gran      psteps/s_cpu (CPU time of the loop, CLOCK_PROCESS_CPUTIME_ID) and psteps/s_wall
#   LIGGGHTS  "Loop time of X on 1 procs for S steps with N atoms" (wall): psteps/s_wall = N S / X;
#             LIGGGHTS 3.8 prints no "% CPU use", so vibrated_bed.in calls cpu_mark.sh just before
#             and just after the timed run, and the CPU share c = (CPU time) / (wall time) between
#             the two marks gives psteps/s_cpu = N S / (X c), as bench/lammps/compare.sh does with
#             LAMMPS's own CPU share
# Prints one line per run and, per size, the medians and the median of the pairwise ratios
# gran / LIGGGHTS (CPU and wall).
set -euo pipefail

runs=${1:-5}
sizes=${2:-100,1600,10000}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
gran=${GRAN_BENCH_DEM:-$root/build/gran_bench_dem}
lig=${LIGGGHTS:-liggghts}
warmup=${WARMUP_PERIODS:-2}
out=${OUT:-$(mktemp -d /tmp/gran-vs-liggghts.XXXXXX)}
mkdir -p "$out"
export OMP_NUM_THREADS=1

# shellcheck source=../peer_compare.sh
source "$here/../peer_compare.sh"

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(getconf _NPROCESSORS_ONLN) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# gran: $gran; LIGGGHTS: $(cd "$out" && "$lig" -h -log none | sed -n 1p | xargs); W = $W; outputs in $out"
same_pages_line
printf '%6s %3s %14s %14s %14s %14s %9s %9s\n' N run gran_cpu gran_wall liggghts_cpu liggghts_wall \
    ratio_cpu ratio_wall
for n in ${sizes//,/ }; do
    psteps=$(psteps_for "$n")
    : >"$out/ratios_$n.txt"
    for ((r = 1; r <= runs; ++r)); do
        g="$out/gran_${n}_$r.txt"
        l="$out/liggghts_${n}_$r.txt"
        c="$out/liggghts_cpu_${n}_$r.txt"
        rm -f "$c"
        read -r gc gw < <(run_gran "$n" "$psteps" "$g")
        # from $out, so that nothing (log.liggghts and the like) lands in the caller's directory
        (cd "$out" && "$lig" -in "$here/vibrated_bed.in" -log none -var dir "$here" -var N "$n" \
            -var psteps "$psteps" -var warmup_periods "$warmup" -var W "$W" -var cpufile "$c" >"$l" 2>&1)
        # CPU share of the timed run from the marks "before CPU WALL" and "after CPU WALL"
        share=$(awk '$1 == "before" {c0 = $2; w0 = $3} $1 == "after" {c1 = $2; w1 = $3}
                     END {printf "%.6f\n", (c1 - c0) / (w1 - w0)}' "$c")
        # the first "Loop time" after the warm-up summary is the timed run's
        read -r lc lw < <(awk -v share="$share" '
            /^vibrated_bed: after a warm-up/ {timed = 1; next}
            timed && /^Loop time of/ && !x {x = $4; s = $9; natoms = $12}
            END {printf "%.6g %.6g\n", natoms * s / (x * share), natoms * s / x}' "$l")
        if [[ -z $gc || -z $lc || $lc == 0 || $lc == nan || $lc == inf ]]; then
            echo "N = $n run $r: no timing read; see $g and $l" >&2
            exit 1
        fi
        record "$n" "$r" "$gc" "$gw" "$lc" "$lw" "$share"
    done
    print_medians "$n"
done
echo "# load at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
