#!/bin/bash
# What `gran study` adds to each run (issue 18, docs/cluster.md): 1000 runs of a scene that does
# almost nothing (20 disks, one collision per particle), one at a time (-j 1), against the same
# scene run 100 times by a shell loop. The difference per run is the study's own cost: loading
# and checking every run's scene, the reuse check, starting and waiting for each run, the merge.
# With an MPI build, the same study under `mpirun -np 2` too (wall time on two ranks).
#   bench/study_overhead.sh BUILD_DIR [RUNS]
set -euo pipefail
gran=$(realpath "${1:-build}")/gran
runs=${2:-1000}
work=$(mktemp -d /tmp/gran-study-overhead.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
cat > tiny.yaml <<'SCENE'
dimension: 2
species: [{name: a, count: 20}]
box: {packing_fraction: 0.05}
observables: [{type: temperatures}]
run: {equilibration: 0, measurement: 1}
SCENE
printf 'scene: tiny.yaml\nreplicas: %s\n' "$runs" > study.yaml
now() { date +%s.%N; }
t0=$(now)
for i in $(seq 1 100); do "$gran" -q run tiny.yaml -o "loop/r$i.h5" --set seed="$i" >/dev/null; done
t1=$(now)
"$gran" -q study study.yaml -o study -j 1 >/dev/null
t2=$(now)
"$gran" -q study study.yaml -o study -j 1 >/dev/null   # everything reused: load, check, merge
t3=$(now)
awk -v a="$t0" -v b="$t1" -v c="$t2" -v d="$t3" -v n="$runs" 'BEGIN {
  run = (b - a) / 100; study = (c - b) / n;
  printf "one gran run by a shell loop:        %6.1f ms\n", 1000 * run;
  printf "per run of a %d-run study, -j 1:   %6.1f ms\n", n, 1000 * study;
  printf "the study'"'"'s own cost per run:         %6.1f ms\n", 1000 * (study - run);
  printf "rerun, all %d reused (load+merge): %6.1f ms per run\n", n, 1000 * (d - c) / n }'
if command -v mpirun >/dev/null && "$gran" study --help | grep -q -- "--slurm"; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  t4=$(now)
  mpirun -np 2 --oversubscribe "$gran" -q study study.yaml -o mpi >/dev/null
  t5=$(now)
  "$gran" -q study study.yaml -o local2 -j 2 >/dev/null
  t6=$(now)
  awk -v a="$t4" -v b="$t5" -v c="$t6" -v n="$runs" 'BEGIN {
    printf "wall per run, mpirun -np 2:          %6.1f ms\n", 1000 * (b - a) / n;
    printf "wall per run, local -j 2:            %6.1f ms\n", 1000 * (c - b) / n }'
fi
