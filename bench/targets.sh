#!/usr/bin/env bash
# Every row of issue 15's target table (docs/performance.md, "Issue 15's targets"), one after
# another, on an otherwise idle machine: about 30 minutes on the 2-core host of 2026-12-07.
#
#   bench/targets.sh EDMD_PATH [BUILD_DIR]     (EDMD_PATH: a clone of FSmallenburg/EDMD outside
#                                               this repository; BUILD_DIR default build)
#
# Needs lmp (Debian's lammps: `make bench-peers` installs it). Prints each step's summary lines;
# the full outputs of the peer scripts stay in their /tmp directories (named in their output).
set -uo pipefail
EDMD=${1:?usage: bench/targets.sh EDMD_PATH [BUILD_DIR]}
cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 1
B=$(cd "${2:-build}" && pwd) || exit 1  # absolute: the peer scripts change directory
geometries=2d_phi0.1,2d_phi0.5,3d_phi0.1,3d_phi0.3
echo "### issue 15's targets at $(git rev-parse --short HEAD 2>/dev/null || echo '?'), $(date -u)"
echo "### 1. gran / EDMD, N = 10^4, both codes at once, cores swapped every round"
GRAN_BENCH="$B/gran_bench" AT_ONCE=1 bench/edmd/compare.sh "$EDMD" 4 0.1,0.2,0.3,0.4,0.5 10976 2>&1 | tail -6
echo "### 2. gran / EDMD, N = 10^4, one after the other"
GRAN_BENCH="$B/gran_bench" bench/edmd/compare.sh "$EDMD" 3 0.1,0.2,0.3,0.4,0.5 10976 2>&1 | tail -6
echo "### 3. cost per collision at 10^6 and 10^4, and memory (B/part), one core, twice"
for _ in 1 2; do
  taskset -c 0 "$B/gran_bench" --dimension 3 --packing-fraction 0.2 --n 1e4,1e6 2>&1 | grep -E '^3d'
  taskset -c 0 "$B/gran_bench" --dimension 2 --packing-fraction 0.5 --n 1e4,1e6 2>&1 | grep -E '^2d'
done
echo "### 4. heated gas over the unheated one, twice"
for _ in 1 2; do
  taskset -c 0 "$B/gran_bench_features" --quick --no-minimal --only thermostat,inelastic \
    --geometries "$geometries" 2>&1 | grep -E 'thermostat +inelastic'
done
echo "### 5. gran / LAMMPS, vibrated bed"
GRAN_BENCH_DEM="$B/gran_bench_dem" bench/lammps/compare.sh 3 100,1600,10000 2>&1 | grep -E ' med '
echo "### 6. gran / LAMMPS, settled bed"
GRAN_BENCH_DEM="$B/gran_bench_dem" W=0 WARMUP_PERIODS=10 bench/lammps/compare.sh 3 1600 2>&1 |
  grep -E '^ +1600 '
echo "### 7. DEM on 2 threads against 1, N = 10^5 (and the state hashes)"
CASES="100000 9 1 4e8" bench/dem_threads.sh "$B" 2 2>&1 | tail -3
echo "### 8. gran / EDMD, N = 108000, one after the other"
GRAN_BENCH="$B/gran_bench" bench/edmd/compare.sh "$EDMD" 2 0.1,0.2,0.3,0.4 108000 2>&1 | tail -5
echo "### 9. gran / LAMMPS, vibrated bed, N = 10^5"
GRAN_BENCH_DEM="$B/gran_bench_dem" bench/lammps/compare.sh 2 100000 2>&1 | grep -E '^100000 '
echo "### done $(date -u)"
