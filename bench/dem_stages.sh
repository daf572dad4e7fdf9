#!/usr/bin/env bash
# Where a DEM step's time goes, measured with the engine's stage clock (gran_bench_dem --stages,
# DemEngine::time_stages), on 1 and 2 threads, alternating: the vibrated bed (W = 9, one period
# of warm-up) at N = 10^4 and 10^5, and the bed settled on a static floor (W = 0, ten periods)
# at N = 1600 (one thread only: a run gives each thread at least 4096 grains,
# DemSettings::min_particles_per_thread) and 10^4. Per run: the wall-clock rate, the state hash
# (the same on 1 and 2 threads), the stages in wall-clock nanoseconds per particle-step, and on 2
# threads the halo grains and the list search's imbalance (max / mean work).
#
#   bench/dem_stages.sh [BUILD_DIR] [ROUNDS]   (ROUNDS default 2: about 10 minutes; needs an
#                                               otherwise idle machine)
B=${1:-build}/gran_bench_dem
ROUNDS=${2:-2}
for case in "10000 9 1 2e8 1,2" "100000 9 1 4e8 1,2" "1600 0 10 1e8 1" "10000 0 10 1e8 1,2"; do
  set -- $case
  args="--sizes $1 --W $2 --warmup-periods $3 --particle-steps $4"
  for round in $(seq "$ROUNDS"); do
    for threads in ${5//,/ }; do
      out=$("$B" $args --threads "$threads" --stages) || exit 1
      row=$(echo "$out" | grep -v '^#' | tail -1)
      printf "N=%s W=%s threads=%s round %s: %s psteps/s (wall), contacts/N %s, hash %s\n  %s\n" \
        "$1" "$2" "$threads" "$round" "$(echo "$row" | awk '{print $5}')" \
        "$(echo "$row" | awk '{print $7}')" "$(echo "$row" | awk '{print $NF}')" \
        "$(echo "$out" | grep -E '^# (stages|thread shares)')"
    done
  done
done
