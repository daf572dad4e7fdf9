#!/bin/sh
# Strong scaling of one DEM run (engine.threads): the vibrated bed of gran_bench_dem (W = 9) at
# N = 10^4 and 10^5, and the bed settled on a static floor (W = 0, 10 periods after the drop) at
# N = 10^4; 1 and 2 threads alternating, twice, one process per run. The speed-up is the ratio of the psteps/s_wall columns
# of neighbouring lines; the state_hash column is the same for 1 and 2 threads (no bit changes).
#
#   bench/dem_threads.sh [BUILD_DIR]      (about 15 minutes on 2 cores; needs an idle machine)
B=${1:-build}/gran_bench_dem
for case in "10000 9 1 1e8" "100000 9 1 4e8" "10000 0 10 1e8"; do
  set -- $case
  for rep in 1 2; do
    for t in 1 2; do
      printf "N=%s W=%s threads=%s rep=%s: " "$1" "$2" "$t" "$rep"
      "$B" --sizes "$1" --W "$2" --warmup-periods "$3" --particle-steps "$4" --threads "$t" | tail -1
    done
  done
done
