#!/bin/sh
# cpu_mark.sh FILE LABEL: appends "LABEL cpu_seconds wall_seconds" for the nearest ancestor process
# named liggghts (the LIGGGHTS run that called this through its "shell" command) to FILE.
# cpu_seconds: the on-CPU time of all its threads (/proc/PID/task/*/schedstat, nanoseconds), as
# gran's CLOCK_PROCESS_CPUTIME_ID; wall_seconds: the epoch time. Used by vibrated_bed.in with
# -var cpufile FILE around the timed run (bench/liggghts/README.md).
file=$1
label=$2
pid=$PPID
while [ "$pid" -gt 1 ] && [ "$(cat /proc/$pid/comm)" != liggghts ]; do
    pid=$(awk '{print $4}' /proc/$pid/stat)
done
if [ "$pid" -le 1 ]; then
    echo "cpu_mark.sh: no liggghts process above $$" >&2
    exit 1
fi
wall=$(date +%s.%N)
cpu=$(cat /proc/$pid/task/*/schedstat | awk '{s += $1} END {printf "%.9f", s / 1e9}')
echo "$label $cpu $wall" >>"$file"
