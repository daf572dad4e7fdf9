#!/bin/bash
# `make test-cluster` (issue 18): a study on a real single-node SLURM cluster (Debian's slurmctld,
# slurmd and munge on localhost, tests/cluster/slurm_cluster.sh). The study (4 runs of about 7
# CPU seconds) is submitted as a job array with a merge job after it; one task is sent the batch
# system's time-limit warning (TERM to its batch shell) midway through its run: the run writes
# its checkpoint and stops, the task resubmits itself and a merge, and the resubmitted task
# resumes the run. Passes when every run completed, one of them resumed once, and the merged
# results are bit for bit those of the same study run locally.
#   tests/cluster/test_slurm_study.sh BUILD_DIR
set -euo pipefail
build=$(realpath "${1:-build}")
src=$(realpath "$(dirname "$0")/../..")
gran="$build/gran"
work=$(mktemp -d /tmp/gran-slurm-test.XXXXXX)
cluster="$work/cluster"
fail() { echo "test-cluster: FAILED: $*" >&2; exit 1; }
passed=0
cleanup() {
  "$src/tests/cluster/slurm_cluster.sh" stop "$cluster" || true
  cd /
  if [ "$passed" = 1 ]; then rm -rf "$work"; else echo "test-cluster: kept $work"; fi
}
trap cleanup EXIT

conf=$("$src/tests/cluster/slurm_cluster.sh" start "$cluster") || fail "the cluster did not start"
export "$conf"
echo "test-cluster: cluster up ($SLURM_CONF)"
sinfo

cd "$work"
cat > gas.yaml <<'SCENE'
dimension: 2
particles: 1000
species:
  - {name: heavy, mass: 3, number_fraction: 0.5}
  - {name: light, mass: 1, number_fraction: 0.5}
interactions: {alpha: 0.85}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat}]
observables: [{type: temperatures}, {type: velocity_pdf}]
run: {equilibration: 20, measurement: 8000}
SCENE
printf 'scene: gas.yaml\nreplicas: 4\n' > study.yaml

echo "test-cluster: the same study locally, the reference"
"$gran" -q study study.yaml -o local -j 2 >/dev/null

echo "test-cluster: submitting"
"$gran" study study.yaml -o slurm --slurm --time 10:00
array=$(awk '/^array/ {print $2}' slurm/slurm/jobs.txt | head -1)
[ -n "$array" ] || fail "no array job recorded"

# Task 0 midway: its run has started measuring (its log exists for a second or more).
for _ in $(seq 600); do
  state=$(squeue -h -j "${array}_0" -o %T 2>/dev/null || true)
  [ "$state" = RUNNING ] && [ -e slurm/logs/gas_r1.log ] && break
  sleep 0.05
done
sleep 2
[ "$(squeue -h -j "${array}_0" -o %T)" = RUNNING ] || fail "task 0 finished before it could be stopped: make the runs longer"
echo "test-cluster: the time-limit warning to task ${array}_0"
# (scancel exits non-zero after signalling an array task on this SLURM: its status is not the test)
scancel --signal=TERM --batch "${array}_0" || true

# Everything leaves the queue: the array, the resubmitted task and the merges.
for _ in $(seq 900); do
  [ -z "$(squeue -h -o %i)" ] && break
  sleep 0.2
done
[ -z "$(squeue -h -o %i)" ] || fail "jobs still queued after 180 s: $(squeue)"
sleep 1

"$gran" study study.yaml -o slurm --status
grep -q "resubmitted as" slurm/slurm/jobs.txt || fail "task 0 was not resubmitted: $(cat slurm/slurm/jobs.txt)"
[ -f slurm/study.study.h5 ] || fail "no merged study"
/usr/bin/python3 - <<'PY' || fail "the resumed run, the placement records or the merged file are wrong"
import h5py
import numpy
runs = [f"gas_r{k}" for k in range(1, 5)]
with h5py.File("slurm/study.study.h5") as f:
    merged = list(f["summary/runs"].asstr()[()])
    assert merged == runs, merged
    resumes = {r: int(f[f"points/{r}/performance/resumes"][()]) for r in runs}
    assert resumes["gas_r1"] == 1 and sum(resumes.values()) == 1, resumes
    tasks = {r: f[f"points/{r}/provenance"].attrs["slurm_array_task_id"] for r in runs}
    assert tasks == {"gas_r1": "0", "gas_r2": "1", "gas_r3": "2", "gas_r4": "3"}, tasks
    # The merged file holds each run's final result file whole (two merge jobs that ran at once
    # once left zeros in the first run's copy).
    for r in runs:
        with h5py.File(f"slurm/{r}.h5") as run:
            paths = []
            run.visititems(lambda name, obj: paths.append(name)
                           if isinstance(obj, h5py.Dataset) else None)
            assert paths, r
            for name in paths:
                a = numpy.asarray(run[name][()])
                b = numpy.asarray(f[f"points/{r}/{name}"][()])
                same = a.shape == b.shape and (a.tolist() == b.tolist() if a.dtype.kind == "O"
                                               else a.tobytes() == b.tobytes())
                assert same, f"points/{r}/{name} differs from {r}.h5"
print("test-cluster: gas_r1 resumed once; each run records its array task; the merged file "
      "holds every run's result")
PY
# (Whether the two merge jobs overlapped this time: timing, not the test.)
if grep -q "another merge" slurm/slurm/logs/merge_*.out; then
  echo "test-cluster: the two merge jobs overlapped; the later one waited for the other"
fi
/usr/bin/python3 "$src/tests/regression/compare_result_dirs.py" slurm local || fail "the SLURM results differ from the local ones"
echo "test-cluster: PASSED"
passed=1
