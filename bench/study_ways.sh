#!/bin/bash
# The Barrat-Trizac tables study three ways, one after the other (docs/cluster.md): one process
# (-j 1), mpirun -np 2, local -j 2; prints the wall seconds of each.
#   bench/study_ways.sh BUILD_DIR
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$(dirname "$0")/.."
GRAN=$(realpath "${1:-build}")/gran
S=studies/barrat-trizac-2002/tables.yaml
rm -rf /tmp/bt-j1 /tmp/bt-mpi /tmp/bt-j2  # nothing reused
t() { local s=$(date +%s.%N); "$@" > /dev/null 2>&1; local e=$(date +%s.%N); echo "$(echo "$e - $s" | bc)"; }
echo "j1 $(t "$GRAN" -q study $S -o /tmp/bt-j1 -j 1)"
echo "mpi2 $(t mpirun -np 2 --oversubscribe "$GRAN" -q study $S -o /tmp/bt-mpi)"
echo "j2 $(t "$GRAN" -q study $S -o /tmp/bt-j2 -j 2)"
