#!/usr/bin/env bash
# Strong scaling of one DEM run (engine.threads): the vibrated bed of gran_bench_dem (W = 9) at
# N = 10^4 and 10^5, and the bed settled on a static floor (W = 0, 10 periods after the drop) at
# N = 10^4. Each round of a case runs, one after another:
#   1. one run on 1 thread (its wall-clock rate: the reference of the round);
#   2. one run on 2 threads: "2 threads / 1" is its wall rate over run 1's;
#   3. two independent 1-thread runs at once: "2 runs / 1" is the sum of their rates over run 1's;
#   4. one 1-thread run pinned to each core (taskset): "2 threads / pinned" is run 2's rate over
#      the mean of the two.
# The third is what this machine gives two copies of the same work at once: the ceiling for
# two threads, if they shared nothing. The fourth matters where the cores run at different
# speeds (docs/performance.md, "Which core"): two threads wait for the slower core, while run 1
# lands on either. CASES="N W WARMUP PSTEPS;..." replaces the three cases. The state hash of every run of a case is printed and must
# be the same (no bit depends on the thread count). The last line of each case gives the medians.
#
#   bench/dem_threads.sh [BUILD_DIR] [ROUNDS]   (ROUNDS default 3: about 35 minutes; needs an
#                                                otherwise idle machine)
B=${1:-build}/gran_bench_dem
ROUNDS=${2:-3}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# rate FILE: the wall-clock psteps/s column of gran_bench_dem's result line.
rate() { tail -1 "$1" | awk '{print $5}'; }
hash_of() { tail -1 "$1" | awk '{print $NF}'; }
# median (of the numbers on stdin), shared with the peer comparisons.
# shellcheck source=peer_compare.sh
source "$(dirname "${BASH_SOURCE[0]}")/peer_compare.sh"
IFS=';' read -r -a cases <<< "${CASES:-10000 9 1 1e8;100000 9 1 4e8;10000 0 10 1e8}"
for case in "${cases[@]}"; do
  set -- $case
  args="--sizes $1 --W $2 --warmup-periods $3 --particle-steps $4"
  : > "$TMP/threads" ; : > "$TMP/pair" ; : > "$TMP/pinned"
  for round in $(seq "$ROUNDS"); do
    "$B" $args --threads 1 > "$TMP/one" || exit 1
    "$B" $args --threads 2 > "$TMP/two" || exit 1
    "$B" $args --threads 1 > "$TMP/a" & pa=$!
    "$B" $args --threads 1 > "$TMP/b" || exit 1
    wait $pa || exit 1
    taskset -c 0 "$B" $args --threads 1 > "$TMP/c0" || exit 1
    taskset -c 1 "$B" $args --threads 1 > "$TMP/c1" || exit 1
    r0=$(rate "$TMP/c0"); rc1=$(rate "$TMP/c1")
    p=$(awk -v a="$(rate "$TMP/two")" -v x="$r0" -v y="$rc1" 'BEGIN {printf "%.2f", a / ((x + y) / 2)}')
    echo "$p" >> "$TMP/pinned"
    r1=$(rate "$TMP/one"); r2=$(rate "$TMP/two"); ra=$(rate "$TMP/a"); rb=$(rate "$TMP/b")
    s=$(awk -v a="$r2" -v b="$r1" 'BEGIN {printf "%.2f", a / b}')
    c=$(awk -v a="$ra" -v b="$rb" -v r="$r1" 'BEGIN {printf "%.2f", (a + b) / r}')
    echo "$s" >> "$TMP/threads"; echo "$c" >> "$TMP/pair"
    printf "N=%s W=%s round %s: 1 thread %s, 2 threads %s, two runs %s + %s psteps/s (wall) | 2 threads / 1 = %s | 2 runs / 1 = %s | 1 thread on core 0, 1: %s, %s | 2 threads / pinned = %s | hashes %s %s %s %s %s %s\n" \
      "$1" "$2" "$round" "$r1" "$r2" "$ra" "$rb" "$s" "$c" "$r0" "$rc1" "$p" \
      "$(hash_of "$TMP/one")" "$(hash_of "$TMP/two")" "$(hash_of "$TMP/a")" "$(hash_of "$TMP/b")" \
      "$(hash_of "$TMP/c0")" "$(hash_of "$TMP/c1")"
  done
  printf "N=%s W=%s: median 2 threads / 1 = %s [%s-%s] | median 2 runs / 1 = %s | median 2 threads / pinned = %s\n" "$1" "$2" \
    "$(median < "$TMP/threads")" "$(sort -g "$TMP/threads" | head -1)" \
    "$(sort -g "$TMP/threads" | tail -1)" "$(median < "$TMP/pair")" "$(median < "$TMP/pinned")"
done
