# shellcheck shell=bash
# Sourced by the peer comparisons (bench/edmd/compare.sh, bench/peer_compare.sh): gran and the
# peer on the same memory pages. gran puts its arrays on transparent huge pages where the
# kernel's THP mode is `madvise`, by setting glibc.malloc.hugetlb=1 for itself
# (libgran/core/huge_pages.hpp); a peer gets that only from the environment. So the tunable is
# exported here for both sides, and gran, finding it set, does not re-execute itself.
# PEER_HUGE_PAGES=0 turns huge pages off for both (GRAN_HUGE_PAGES=0, no tunable added).
if [[ ${PEER_HUGE_PAGES:-1} == 0 ]]; then
    export GRAN_HUGE_PAGES=0
else
    case ":${GLIBC_TUNABLES:-}:" in
        *:glibc.malloc.hugetlb=*) ;;
        *) export GLIBC_TUNABLES=${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.malloc.hugetlb=1 ;;
    esac
fi
# same_pages_line: the header line saying what both sides ran with
same_pages_line() {
    local thp
    thp=$(cat /sys/kernel/mm/transparent_hugepage/enabled 2>/dev/null || echo '?')
    if [[ ${PEER_HUGE_PAGES:-1} == 0 ]]; then
        echo "# pages: huge pages off for both (GRAN_HUGE_PAGES=0, GLIBC_TUNABLES='${GLIBC_TUNABLES:-}'); THP: $thp"
    else
        echo "# pages: GLIBC_TUNABLES=$GLIBC_TUNABLES for both sides; THP: $thp"
    fi
}
