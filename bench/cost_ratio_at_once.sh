#!/usr/bin/env bash
# Issue 15's cost per collision at 10^6 over that at 10^4 (event-driven, one core), with both
# sizes running at the same time on the two cores (then swapped), so that both see the same
# machine state: one 10^6 run (--quick: 2 x 10^6 timed collisions) on one core, and 10^4 runs
# one after another on the other core for as long as it lasts (their median rate is taken).
# Sharing the machine slows the 10^4 runs too (about 6e5 collisions/s here, against 1.2e6 alone
# in its fast state), so the ratio reads lower than from runs alone; compare ratios of this
# script with each other.
#
#   bench/cost_ratio_at_once.sh D PHI [BUILD_DIR]    e.g. bench/cost_ratio_at_once.sh 3 0.2 build
#   GRAN_HUGE_PAGES=0 bench/cost_ratio_at_once.sh ... (without transparent huge pages)
D=$1
PHI=$2
B=${3:-build}/gran_bench
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in 1 2; do
  if [ $r = 1 ]; then small=0; large=1; else small=1; large=0; fi
  taskset -c $large "$B" --dimension "$D" --packing-fraction "$PHI" --n 1e6 --quick > "$tmp/large" 2>&1 &
  big=$!
  : > "$tmp/small"
  while kill -0 $big 2>/dev/null; do
    taskset -c $small "$B" --dimension "$D" --packing-fraction "$PHI" --n 1e4 --quick 2>&1 |
      grep _N >> "$tmp/small"
  done
  wait
  L=$(grep _N "$tmp/large" | awk '{print $5}')
  S=$(awk '{print $5}' "$tmp/small" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  echo "D=$D phi=$PHI round $r: 10^4 median $S collisions/s of $(wc -l < "$tmp/small") runs" \
    "(core $small), 10^6 $L (core $large), ratio $(awk -v s="$S" -v l="$L" 'BEGIN {printf "%.2f", s / l}')" \
    "(GRAN_HUGE_PAGES=${GRAN_HUGE_PAGES:-default})"
done
