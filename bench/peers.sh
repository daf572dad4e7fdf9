#!/bin/bash
# `make bench-peers`: gran against its peers, side by side in one run, one core each (serial runs,
# alternating), ratios of each code's own timing of its timed loop (CPU time):
#   1. event-driven: Smallenburg's EDMD (bench/edmd/compare.sh), 3D elastic spheres, when EDMD is
#      set to a clone of github.com/FSmallenburg/EDMD outside this repository (skipped otherwise);
#   2. DEM: LAMMPS and LIGGGHTS from Debian (bench/lammps, bench/liggghts), the vibrated bed
#      (W = 9) and the bed settled on a static floor (W = 0, about 5 contacts per grain).
#
#   bench/peers.sh            (environment below; make bench-peers EDMD=/path/to/EDMD)
#
# Environment: EDMD (path), ROUNDS (3), EDMD_PHIS (0.1,0.2,0.3,0.4,0.5), EDMD_NS (10976,108000),
# DEM_SIZES (100,1600,10000), SETTLED_SIZES (1600), SETTLED_WARMUP (10 periods of the W = 9 drive:
# long enough for the poured grains to come to rest), OUT (a new directory under /tmp).
# PEER_HUGE_PAGES (1: every code with glibc.malloc.hugetlb=1, as gran sets it for itself where the
# kernel's THP mode is madvise; 0: huge pages off for all; bench/same_pages.sh).
# Takes about 15 min with the defaults on this machine class; every run's output stays in $OUT.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rounds=${ROUNDS:-3}
out=${OUT:-$(mktemp -d /tmp/gran-peers.XXXXXX)}
mkdir -p "$out"
echo "# bench/peers.sh: $(date -u +%Y-%m-%dT%H:%MZ), gran $(git -C "$here/.." rev-parse --short HEAD 2>/dev/null || echo '?'), outputs in $out"

summary=()
if [[ -n ${EDMD:-} ]]; then
    OUT="$out/edmd" "$here/edmd/compare.sh" "$EDMD" "$rounds" "${EDMD_PHIS:-0.1,0.2,0.3,0.4,0.5}" \
        "${EDMD_NS:-10976,108000}" | tee "$out/edmd.txt" || summary+=("EDMD comparison FAILED: see $out/edmd")
    while read -r phi n med range; do
        summary+=("$(printf '%-44s %s %s' "event-driven 3D phi $phi, N = $n: gran / EDMD" "$med" "$range")")
    done < <(sed -n '/^# gran \/ EDMD/,$p' "$out/edmd.txt" | tail -n +2)
else
    echo "# EDMD not set: the event-driven comparison is skipped (make bench-peers EDMD=/path/to/EDMD)"
fi

# dem PEER W SIZES WARMUP: one DEM comparison; adds its medians to the summary
dem() {
    local peer=$1 w=$2 sizes=$3 warm=$4 label
    label=$([[ $w == 0 ]] && echo "settled bed" || echo "vibrated bed W = $w")
    if ! command -v "$([[ $peer == lammps ]] && echo "${LMP:-lmp}" || echo "${LIGGGHTS:-liggghts}")" >/dev/null; then
        echo "# $peer not installed (apt-get install $peer): skipped"
        return
    fi
    local log="$out/${peer}_W$w.txt"
    if ! OUT="$out/${peer}_W$w" W=$w WARMUP_PERIODS=$warm "$here/$peer/compare.sh" "$rounds" "$sizes" |
        tee "$log"; then
        summary+=("DEM $label against $peer FAILED: see $out/${peer}_W$w")
        return
    fi
    local gc pc
    while read -r n _ _ _ _ _ rc _; do
        # contacts per grain at the end of the first round's timed run, gran's and the peer's
        gc=$(awk -v n="$n" '$1 == n {print $7}' "$out/${peer}_W$w/gran_${n}_1.txt")
        pc=$(sed -n 's/.*at the end: contacts\/N \([0-9.]*\).*/\1/p' "$out/${peer}_W$w/${peer}_${n}_1.txt")
        summary+=("$(printf '%-44s %s   (contacts per grain: gran %.3f, %s %.3f)' \
            "DEM $label, N = $n: gran / $peer" "$rc" "$gc" "$peer" "$pc")")
    done < <(awk '$2 == "med"' "$log")
}
dem lammps 9 "${DEM_SIZES:-100,1600,10000}" 2
dem lammps 0 "${SETTLED_SIZES:-1600}" "${SETTLED_WARMUP:-10}"
dem liggghts 9 "${DEM_SIZES:-100,1600,10000}" 2
dem liggghts 0 "${SETTLED_SIZES:-1600}" "${SETTLED_WARMUP:-10}"

echo
echo "# summary: ratios of collisions (event-driven) or particle-steps (DEM) per CPU second, one core"
echo "# each, median of $rounds alternating rounds (event-driven: [min-max] of the rounds)"
printf '%s\n' "${summary[@]}"
