#!/bin/bash
# Side-by-side rates of several gran_bench binaries (e.g. a worktree at an earlier commit against
# this build): each round runs every binary once, in turn, with the same arguments, and prints the
# timed collisions per CPU second of each case (and its peak bytes per particle, where the binary
# reports them) with gran_bench's check in brackets (a run whose
# check fails, e.g. a lattice not yet melted after a short --equil, exits non-zero and is still
# printed: read the check before the rate). Alternating keeps the ratios meaningful when the
# shared machine's speed drifts; quote the median of the per-round ratios.
#
#   bench/alternate_rates.sh ROUNDS "GRAN_BENCH_ARGS" BINARY...
#   bench/alternate_rates.sh 3 "--dimension 3 --packing-fraction 0.2 --n 1e6 --quick" \
#       /work/wt-base/build/gran_bench build/gran_bench
# A BINARY may carry its own arguments: "build/gran_bench --cell-layout blocks".
set -euo pipefail
if (($# < 3)); then
    sed -n '2,12p' "$0" >&2
    exit 2
fi
rounds=$1
read -r -a args <<<"$2"
shift 2
for ((r = 1; r <= rounds; ++r)); do
    line="round $r"
    for bin in "$@"; do
        read -r -a cmd <<<"$bin"
        rates=$("${cmd[@]}" "${args[@]}" 2>&1 | awk '
            $1 == "case" {for (k = 1; k <= NF; ++k) if ($k == "B/part") m = k}
            /^[23]d_/ {printf " %s%s [%s]", $5, m ? " (" $m " B/particle)" : "", $NF}' || true)
        line="$line | $bin$rates"
    done
    echo "$line"
done
