#!/usr/bin/env bash
# A/B on a machine whose speed swings: two command lines run at the same time, one per core
# (taskset), then again with the cores swapped, so both see the same machine state. Prints, per
# round, the lines of each output that match PATTERN. For one-thread runs only (each takes a
# core); two independent runs at once keep their solo rates here (docs/performance.md, "Two runs
# at once").
#
#   bench/at_once.sh "COMMAND A" "COMMAND B" PATTERN [ROUNDS]   (ROUNDS default 2)
#
# e.g. huge pages off against on, event-driven gas of 10^6 spheres:
#   bench/at_once.sh "GRAN_HUGE_PAGES=0 build/gran_bench --dimension 3 --packing-fraction 0.2 \
#     --n 1e6 --quick" "build/gran_bench --dimension 3 --packing-fraction 0.2 --n 1e6 --quick" N1000000
A=$1
B=$2
PATTERN=$3
ROUNDS=${4:-2}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $(seq "$ROUNDS"); do
  if [ $((r % 2)) = 1 ]; then ca=0; cb=1; else ca=1; cb=0; fi
  taskset -c $ca bash -c "$A" > "$tmp/a" 2>&1 &
  taskset -c $cb bash -c "$B" > "$tmp/b" 2>&1 &
  wait
  echo "round $r, A on core $ca: $(grep -E "$PATTERN" "$tmp/a" | tr '\n' ' ')"
  echo "round $r, B on core $cb: $(grep -E "$PATTERN" "$tmp/b" | tr '\n' ' ')"
done
