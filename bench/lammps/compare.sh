#!/usr/bin/env bash
# gran's DEM benchmark against LAMMPS on the same vibrated bed (bench/lammps/README.md).
#
#   bench/lammps/compare.sh [RUNS] [SIZES]        e.g. bench/lammps/compare.sh 5 100,1600,10000
#
# Environment: GRAN_BENCH_DEM (default build/gran_bench_dem), LMP (default lmp),
# WARMUP_PERIODS (default 2), W (default 9; 0: the bed settled on a static floor),
# PSTEPS_SMALL (default 2e7, N < 10^4), PSTEPS_LARGE (default 5e7),
# OUT (default a new directory under /tmp: every run's full output is kept there).
# PEER_HUGE_PAGES (default 1: both codes with glibc.malloc.hugetlb=1, bench/same_pages.sh; 0: neither).
#
# Runs gran and LAMMPS alternately, RUNS times each per size, serially (one process each,
# OMP_NUM_THREADS=1), with equal warm-up and equal timed particle-steps, and reads each code's own
# timing of its timed loop:
#   gran    psteps/s_cpu (CPU time of the loop, CLOCK_PROCESS_CPUTIME_ID) and psteps/s_wall
#   LAMMPS  "Loop time of X on 1 procs for S steps with N atoms" (wall) and the "% CPU use" printed
#           under it: psteps/s_wall = N S / X, psteps/s_cpu = N S / (X * CPU% / 100)
# Prints one line per run and, per size, the medians and the median of the pairwise ratios
# gran / LAMMPS (CPU and wall).
set -euo pipefail

runs=${1:-5}
sizes=${2:-100,1600,10000}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
gran=${GRAN_BENCH_DEM:-$root/build/gran_bench_dem}
lmp=${LMP:-lmp}
warmup=${WARMUP_PERIODS:-2}
out=${OUT:-$(mktemp -d /tmp/gran-vs-lammps.XXXXXX)}
mkdir -p "$out"
export OMP_NUM_THREADS=1

# shellcheck source=../peer_compare.sh
source "$here/../peer_compare.sh"

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(getconf _NPROCESSORS_ONLN) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "# gran: $gran; LAMMPS: $($lmp -h | sed -n 2p | xargs); W = $W; outputs in $out"
same_pages_line
printf '%6s %3s %14s %14s %14s %14s %9s %9s\n' N run gran_cpu gran_wall lammps_cpu lammps_wall \
    ratio_cpu ratio_wall
for n in ${sizes//,/ }; do
    psteps=$(psteps_for "$n")
    : >"$out/ratios_$n.txt"
    for ((r = 1; r <= runs; ++r)); do
        g="$out/gran_${n}_$r.txt"
        l="$out/lammps_${n}_$r.txt"
        read -r gc gw < <(run_gran "$n" "$psteps" "$g")
        "$lmp" -in "$here/vibrated_bed.in" -log none -var N "$n" -var psteps "$psteps" \
            -var warmup_periods "$warmup" -var W "$W" >"$l" 2>&1
        # the first "Loop time" after the warm-up summary is the timed run's
        read -r lc lw < <(awk '
            /^vibrated_bed: after a warm-up/ {timed = 1; next}
            timed && /^Loop time of/ && !x {x = $4; s = $9; natoms = $12; next}
            timed && x && /% CPU use/ && !c {c = $1; sub("%", "", c)}
            END {printf "%.6g %.6g\n", natoms * s / (x * c / 100), natoms * s / x}' "$l")
        record "$n" "$r" "$gc" "$gw" "$lc" "$lw"
    done
    print_medians "$n"
done
