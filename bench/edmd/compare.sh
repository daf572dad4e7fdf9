#!/bin/bash
# gran's event-driven engine against Smallenburg's EDMD (Eur. Phys. J. E 45, 22 (2022); the
# "Single" variant: neighbour lists with a skin, one event per particle, calendar queue), side by
# side: elastic monodisperse spheres, periodic cube, FCC/lattice start, 20 collisions per particle
# of equilibration, then the same number of timed collisions as gran_bench (max(2e6, 20 N)).
#
#   bench/edmd/compare.sh EDMD_DIR [ROUNDS] [PHIS] [NS]
#   bench/edmd/compare.sh /work/.mirror/FSmallenburg+EDMD/repo 3 0.1,0.2,0.3,0.4,0.5 10976,108000
#
# EDMD_DIR is a checkout (or the bare git directory `fetch` gives) of github.com/FSmallenburg/EDMD,
# outside this repository; nothing of it is copied here. Its parameters are global variables of
# Single/mdSingle.c, so for each (phi, N) a copy in $OUT is edited with sed (FCC start, packing
# fraction, N, run time, its thermostat off, and a print of the process CPU clock at each of its
# "write" events) and compiled with the peer's own flags (its Makefile: -Ofast -funroll-loops
# -march=native; override with EDMD_CFLAGS). EDMD's rate is (collisions between the writes at the
# end of equilibration and at the end) / (CPU time between them); gran's is gran_bench's timed loop
# (CPU time). N must be 4 k^3 (EDMD's FCC). Each round runs gran then EDMD; the ratio printed last
# is the median of the per-round ratios, with min-max. Both run with glibc.malloc.hugetlb=1
# (bench/same_pages.sh; PEER_HUGE_PAGES=0: neither). AT_ONCE=1: each round runs the two at the
# same time, one per core (taskset), the cores swapped from round to round (use an even number of
# rounds): on a host whose two cores run at different speeds, and change speed, this compares the
# codes on the same cores at the same moment (docs/performance.md, "Which core"). The geometric
# mean of the rounds' ratios is printed beside the median: with an even number of rounds at once
# it weighs both cores alike. At 10^5 particles and more the two runs share the last-level cache
# and the memory bus, so AT_ONCE=1 is for sizes whose state fits in each core's own caches.
set -euo pipefail
if (($# < 1)); then
    sed -n '2,19p' "$0" >&2
    exit 2
fi
edmd=$1
rounds=${2:-3}
phis=${3:-0.1,0.2,0.3,0.4,0.5}
ns=${4:-10976,108000}
at_once=${AT_ONCE:-0}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
gran=${GRAN_BENCH:-$root/build/gran_bench}
out=${OUT:-$(mktemp -d /tmp/gran-vs-edmd.XXXXXX)}
cflags=${EDMD_CFLAGS:--Wall -Ofast -funroll-loops -march=native}
mkdir -p "$out"
# shellcheck source=../same_pages.sh
source "$here/../same_pages.sh"

# The peer's source: a work tree, or the bare repository `fetch` gives.
if [[ -f $edmd/Single/mdSingle.c ]]; then
    cp "$edmd/Single/"{mdSingle.c,mdSingle.h,mt19937ar.c} "$out/"
    commit=$(git -C "$edmd" rev-parse --short HEAD 2>/dev/null || echo "work tree")
elif git -C "$edmd" rev-parse --verify -q HEAD >/dev/null; then
    for f in mdSingle.c mdSingle.h mt19937ar.c; do git -C "$edmd" show "HEAD:Single/$f" >"$out/$f"; done
    commit=$(git -C "$edmd" rev-parse --short HEAD)
else
    echo "bench/edmd/compare.sh: $edmd has no Single/mdSingle.c (expected a clone of FSmallenburg/EDMD)" >&2
    exit 2
fi
pristine="$out/mdSingle.c"
mv "$pristine" "$out/mdSingle.orig.c"

median() { sort -g | awk '{a[NR] = $1} END {if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

# times PHI N: "equilibration_end write_interval max_time" in EDMD's units (sigma = m = kT = 1),
# from the Enskog collision frequency per particle with the Carnahan-Starling contact value,
# omega = 4 n sigma^2 g(sigma) sqrt(pi kT / m); N omega / 2 collisions per unit time.
times() {
    awk -v phi="$1" -v n_part="$2" 'BEGIN {
        pi = atan2(0, -1); n = 6 * phi / pi; g = (1 - phi / 2) / (1 - phi) ^ 3
        omega = 4 * n * g * sqrt(pi); rate = n_part * omega / 2
        timed = (2e6 > 20 * n_part) ? 2e6 : 20 * n_part
        w = timed / rate / 4; ta = w * int(20 * n_part / rate / w + 1)
        printf "%.9g %.9g %.9g\n", ta, w, ta + 4.5 * w }'
}

# build_edmd PHI N: the edited, compiled copy for one case; prints its path
build_edmd() {
    local bin="$out/edmd_phi$1_N$2" src="$out/edmd_phi$1_N$2.c"
    read -r ta w tmax < <(times "$1" "$2")
    sed -e 's/^double maxtime = [^;]*;/double maxtime = '"$tmax"';/' \
        -e 's/^int initialconfig = [^;]*;/int initialconfig = 1;/' \
        -e 's/^double packfrac = [^;]*;/double packfrac = '"$1"';/' \
        -e 's/^int N = [^;]*;/int N = '"$2"';/' \
        -e 's/^double writeinterval = [^;]*;/double writeinterval = '"$w"';/' \
        -e 's/^const int usethermostat = [^;]*;/const int usethermostat = 0;/' \
        -e 's/^\( *\)printf("Simtime: %lf, Collisions: %u,/\1printf("cpu %.6f ", (double)clock() \/ CLOCKS_PER_SEC); printf("Simtime: %lf, Collisions: %u,/' \
        -e '1i #include <time.h>' "$out/mdSingle.orig.c" >"$src"
    for key in 'maxtime = '"$tmax" 'initialconfig = 1' 'packfrac = '"$1" 'int N = '"$2" \
        'usethermostat = 0' 'clock()'; do
        grep -q "$key" "$src" || { echo "bench/edmd/compare.sh: could not set '$key' in EDMD's source" >&2; exit 1; }
    done
    local flags
    read -r -a flags <<<"$cflags"
    (cd "$out" && gcc "${flags[@]}" "$src" -o "$bin" -lm) >&2
    echo "$bin"
}

# run_edmd BIN PHI N ROUND: "rate collisions omega/Enskog" of the timed stretch (writes from ta to
# the last); omega/Enskog as gran_bench's w/Enskog column (collisions per particle per unit time
# over the Carnahan-Starling Enskog value, kT = 1): far from 1 means another state (a crystal)
run_edmd() {
    local log
    log="$out/$(basename "$1")_$4.txt"
    read -r ta w tmax < <(times "$2" "$3")
    (cd "$out" && "$1") >"$log"
    awk -v ta="$ta" -v w="$w" -v phi="$2" -v n_part="$3" '
        /^cpu .*Simtime:/ {
            t = $4; sub(",", "", t); t += 0; c = $6; sub(",", "", c); c += 0
            if (!a && t > ta - w / 2) {a = 1; c0 = c; cpu0 = $2; s0 = t}
            c1 = c; cpu1 = $2; s1 = t }
        END { if (!a || cpu1 <= cpu0) {print "nan 0 nan"; exit}
              pi = atan2(0, -1); n = 6 * phi / pi; g = (1 - phi / 2) / (1 - phi) ^ 3
              printf "%.6g %d %.4f\n", (c1 - c0) / (cpu1 - cpu0), c1 - c0,
                  2 * (c1 - c0) / (n_part * (s1 - s0)) / (4 * n * g * sqrt(pi)) }' "$log"
}

# run_gran PHI N ROUND: "rate w/Enskog check" of gran_bench's timed loop
run_gran() {
    local log="$out/gran_phi$1_N$2_$3.txt"
    "$gran" --dimension 3 --packing-fraction "$1" --n "$2" >"$log" 2>&1 || true
    awk '$1 == "case" {for (k = 1; k <= NF; ++k) if ($k == "w/Enskog") w = k}
        /^3d_/ {printf "%s %s %s\n", $5, $w, $NF}' "$log"
}

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(getconf _NPROCESSORS_ONLN) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "# gran: $gran ($(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?')); EDMD Single $commit, gcc $cflags; outputs in $out"
same_pages_line
printf '%6s %7s %5s %12s %12s %7s %10s %10s %10s %6s\n' phi N round gran_coll/s edmd_coll/s ratio \
    gran_w/En edmd_w/En edmd_timed check
summary=()
for n in ${ns//,/ }; do
    for phi in ${phis//,/ }; do
        bin=$(build_edmd "$phi" "$n")
        : >"$out/ratios_phi${phi}_N$n.txt"
        for ((r = 1; r <= rounds; ++r)); do
            if [[ $at_once == 1 ]]; then
                # Both at once, one per core, the cores swapped every round.
                if ((r % 2)); then cg=0 ce=1; else cg=1 ce=0; fi
                (taskset -p -c "$cg" "$BASHPID" >/dev/null && run_gran "$phi" "$n" "$r") >"$out/g.$r" &
                (taskset -p -c "$ce" "$BASHPID" >/dev/null && run_edmd "$bin" "$phi" "$n" "$r") >"$out/e.$r" &
                wait
                read -r gr gw check <"$out/g.$r"
                read -r er ec ew <"$out/e.$r"
            else
                read -r gr gw check < <(run_gran "$phi" "$n" "$r")
                read -r er ec ew < <(run_edmd "$bin" "$phi" "$n" "$r")
            fi
            ratio=$(awk -v a="$gr" -v b="$er" 'BEGIN {printf "%.3f", a / b}')
            echo "$ratio" >>"$out/ratios_phi${phi}_N$n.txt"
            printf '%6s %7s %5s %12.4g %12.4g %7s %10s %10s %10s %6s\n' "$phi" "$n" "$r" "$gr" "$er" \
                "$ratio" "$gw" "$ew" "$ec" "$check"
        done
        f="$out/ratios_phi${phi}_N$n.txt"
        gmean=$(awk '{s += log($1); k++} END {printf "%.3f", exp(s / k)}' "$f")
        summary+=("$(printf '%6s %7s   %s [%s-%s]   geometric mean %s' "$phi" "$n" "$(median <"$f")" "$(sort -g "$f" | head -1)" "$(sort -g "$f" | tail -1)" "$gmean")")
    done
done
if [[ $at_once == 1 ]]; then how="rounds at once (cores swapped)"; else how="alternating rounds"; fi
echo "# gran / EDMD, collisions per CPU second, median of $rounds $how [min-max]"
printf '%s\n' "${summary[@]}"
