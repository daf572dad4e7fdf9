# Shared by bench/lammps/compare.sh and bench/liggghts/compare.sh (sourced, not run): timing gran's
# DEM benchmark, recording one gran-versus-peer pair of timings, and the per-size medians.
# The caller sets: gran (path of gran_bench_dem), warmup (periods), out (output directory).
# W (environment, default 9): the floor's (A omega)^2 / (g d); 0 is a bed settled on a static floor.
W=${W:-9}
# shellcheck source=same_pages.sh
source "$(dirname "${BASH_SOURCE[0]}")/same_pages.sh"

median() { sort -g | awk '{a[NR] = $1} END {if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

# psteps_for N: timed particle-steps per run (PSTEPS_SMALL below 10^4 grains, PSTEPS_LARGE above)
psteps_for() { if (($1 < 10000)); then echo "${PSTEPS_SMALL:-2e7}"; else echo "${PSTEPS_LARGE:-5e7}"; fi; }

# run_gran N PSTEPS FILE: runs gran_bench_dem, prints "cpu wall" particle-steps per second
run_gran() {
    "$gran" --sizes "$1" --particle-steps "$2" --warmup-periods "$warmup" --W "$W" >"$3" 2>&1
    awk '$1 == '"$1"' {print $4, $5}' "$3"
}

# record N RUN GRAN_CPU GRAN_WALL PEER_CPU PEER_WALL [EXTRA]: appends the pair and its ratios to
# $out/ratios_N.txt and prints one table line
record() {
    local rc rw
    rc=$(awk -v a="$3" -v b="$5" 'BEGIN {printf "%.4f", a / b}')
    rw=$(awk -v a="$4" -v b="$6" 'BEGIN {printf "%.4f", a / b}')
    echo "$3 $4 $5 $6 $rc $rw ${7:-}" >>"$out/ratios_$1.txt"
    printf '%6s %3s %14.4g %14.4g %14.4g %14.4g %9s %9s\n' "$1" "$2" "$3" "$4" "$5" "$6" "$rc" "$rw"
}

# print_medians N: the median of every column of $out/ratios_N.txt
print_medians() {
    local f="$out/ratios_$1.txt"
    printf '%6s %3s %14.4g %14.4g %14.4g %14.4g %9s %9s\n' "$1" med \
        "$(cut -d' ' -f1 "$f" | median)" "$(cut -d' ' -f2 "$f" | median)" \
        "$(cut -d' ' -f3 "$f" | median)" "$(cut -d' ' -f4 "$f" | median)" \
        "$(cut -d' ' -f5 "$f" | median)" "$(cut -d' ' -f6 "$f" | median)"
}
