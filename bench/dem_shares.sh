#!/usr/bin/env bash
# The threads' shares that follow their measured speeds (DemSettings::balance_threads, the
# default) against equal shares (gran_bench_dem --equal-shares), on the vibrated bed. Each round
# runs, one after another: one run on 1 thread (the round's reference), then the two 2-thread
# runs, their order swapped every round (this host's cores and state swing by 1.4-1.7x for
# minutes; docs/performance.md, "Which core"). Prints each rate, each 2-thread run over the
# reference, balanced / equal, the balanced run's fractions of the pair entries at its last
# list build, and the three state hashes (always equal: the cut changes no bit); at the end the
# geometric mean of balanced / equal and the medians of 2 threads / 1.
#
#   bench/dem_shares.sh [BUILD_DIR] [ROUNDS] [N] [PARTICLE_STEPS]   (defaults: build 8 100000
#                                                                    4e8: about 9 minutes)
#
# A controlled slow core: NEIGHBOUR="BUSY SLEEP" runs bench/busy_neighbour.cpp (built into the
# temporary directory) pinned to core 0 during the whole comparison, busy BUSY ms then asleep
# SLEEP ms; BIND=1 binds the threads to the cores (OMP_PROC_BIND=true OMP_PLACES=cores), so
# that thread 0 stays on core 0 with the neighbour.
B=${1:-build}/gran_bench_dem
ROUNDS=${2:-8}
N=${3:-100000}
PSTEPS=${4:-4e8}
TMP=$(mktemp -d)
neighbour=
trap '[[ -n $neighbour ]] && kill "$neighbour"; rm -rf "$TMP"' EXIT
if [[ ${BIND:-0} == 1 ]]; then export OMP_PROC_BIND=true OMP_PLACES=cores; fi
if [[ -n ${NEIGHBOUR:-} ]]; then
  g++ -std=c++20 -O2 "$(dirname "${BASH_SOURCE[0]}")/busy_neighbour.cpp" -o "$TMP/busy_neighbour" || exit 1
  # shellcheck disable=SC2086
  taskset -c 0 "$TMP/busy_neighbour" $NEIGHBOUR & neighbour=$!
  echo "# a neighbour on core 0: busy / asleep $NEIGHBOUR ms; threads bound: ${BIND:-0}"
fi
args="--sizes $N --W 9 --warmup-periods 1 --particle-steps $PSTEPS"
# rate FILE: the wall-clock rate and the state hash of the case's row.
rate() { grep -E "^ +$N " "$1" | awk '{print $5, $NF}'; }
# shellcheck source=peer_compare.sh
source "$(dirname "${BASH_SOURCE[0]}")/peer_compare.sh"
: > "$TMP/ratio"; : > "$TMP/bal"; : > "$TMP/eq"
for r in $(seq "$ROUNDS"); do
  "$B" $args --threads 1 > "$TMP/one" || exit 1
  if (( r % 2 )); then
    "$B" $args --threads 2 --stages > "$TMP/b" || exit 1
    "$B" $args --threads 2 --equal-shares > "$TMP/e" || exit 1
  else
    "$B" $args --threads 2 --equal-shares > "$TMP/e" || exit 1
    "$B" $args --threads 2 --stages > "$TMP/b" || exit 1
  fi
  read -r a ha < <(rate "$TMP/one")
  read -r b hb < <(rate "$TMP/b")
  read -r e he < <(rate "$TMP/e")
  shares=$(grep -o "last build:.*" "$TMP/b" | sed 's/last build: //')
  awk -v a="$a" -v b="$b" -v e="$e" 'BEGIN {printf "%.4f\n", b / e}' >> "$TMP/ratio"
  awk -v a="$a" -v b="$b" 'BEGIN {printf "%.3f\n", b / a}' >> "$TMP/bal"
  awk -v a="$a" -v e="$e" 'BEGIN {printf "%.3f\n", e / a}' >> "$TMP/eq"
  awk -v a="$a" -v b="$b" -v e="$e" -v r="$r" -v s="$shares" -v h="$ha $hb $he" 'BEGIN {
    printf "round %d: 1 thread %.3e, 2 threads balanced %.3e (%.2fx), equal %.3e (%.2fx) psteps/s (wall) | balanced / equal %.3f | shares %s | hashes %s\n",
      r, a, b, b / a, e, e / a, b / e, s, h}'
done
printf "N=%s: balanced / equal, geometric mean %s [%s-%s] | median 2 threads / 1: balanced %s, equal %s\n" "$N" \
  "$(awk '{s += log($1); n++} END {printf "%.3f", exp(s / n)}' "$TMP/ratio")" \
  "$(sort -g "$TMP/ratio" | head -1)" "$(sort -g "$TMP/ratio" | tail -1)" \
  "$(median < "$TMP/bal")" "$(median < "$TMP/eq")"
