#!/usr/bin/env bash
# slurm_test.sh SOURCE_DIR CONTACTLAB_EXE — `contactlab experiment slurm` on a real Slurm (label
# `cluster`). Starts a one-node Slurm from Debian's packages (munged, slurmctld, slurmd, as root,
# every file and socket in a fresh folder, on free ports, so it touches no system Slurm and two of
# these tests can run at once), submits a 4-task array of seed 004's protocol through the script
# the command writes (into a folder whose path holds a space), waits for the merge job, compares
# the merged file with one `experiment run` of the same participants byte for byte, and stops the
# daemons it started. It fails, saying why, when Slurm cannot start here (not root, packages
# missing: scripts/setup installs them): a cluster job that was never submitted proves nothing.
set -euo pipefail
source_dir=$1 exe=$2
protocol="$source_dir/scenes/experiments/004-surface-orientation.json"
t_start=$(date +%s)

fail() { echo "slurm test: FAILED: $*" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || fail "needs root: slurmd starts jobs as their users and munged must run as the Slurm user (CI runs as root)"
for cmd in munged slurmctld slurmd sbatch squeue sinfo scontrol; do
  command -v "$cmd" >/dev/null || fail "no $cmd: install Debian's slurmctld slurmd slurm-client munge (scripts/setup does)"
done

work=$(mktemp -d "${TMPDIR:-/tmp}/contactlab-slurm-XXXXXX")
chmod 700 "$work"
pids=()
stop() {
  local rc=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done   # only the daemons started here, by id
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ $rc -ne 0 ]; then
    for log in "$work"/log/*.log; do [ -f "$log" ] && { echo "== $log"; tail -n 30 "$log"; }; done
    find "$work/study dir" -name '*.out' -exec sh -c 'echo "== $1"; tail -n 30 "$1"' _ {} \; 2>/dev/null || true
  fi
  rm -rf "$work"
  exit $rc
}
trap stop EXIT
mkdir -p "$work/log" "$work/munge" "$work/ctld" "$work/spool" "$work/study dir"

# Two free TCP ports for slurmctld and slurmd (nothing answers on them).
free_port() {
  local p
  while :; do
    p=$((20000 + RANDOM % 20000))
    (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || { echo "$p"; return; }
  done
}
ctld_port=$(free_port)
slurmd_port=$(free_port)
[ "$slurmd_port" != "$ctld_port" ] || slurmd_port=$((ctld_port + 1))

host=$(hostname -s)   # the node's name must be this machine's; its address is given (no DNS needed)
cat >"$work/slurm.conf" <<CONF
ClusterName=contactlab-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/ctld
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=1000 State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"

dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 600 "$work/munge/munge.key"
munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/log/munged.log" --seed-file="$work/munge/seed" ||
  fail "munged did not start (see $work/log/munged.log above)"
pids+=("$(cat "$work/munge/munged.pid")")
slurmctld -f "$SLURM_CONF" -i || fail "slurmctld did not start"
for _ in $(seq 100); do [ -s "$work/slurmctld.pid" ] && break; sleep 0.1; done
[ -s "$work/slurmctld.pid" ] || fail "slurmctld wrote no pid file"
pids+=("$(cat "$work/slurmctld.pid")")
slurmd -f "$SLURM_CONF" -N "$host" || fail "slurmd did not start"
for _ in $(seq 100); do [ -s "$work/slurmd.pid" ] && break; sleep 0.1; done
[ -s "$work/slurmd.pid" ] || fail "slurmd wrote no pid file"
pids+=("$(cat "$work/slurmd.pid")")

# The node idle: the cluster takes jobs.
state=""
for _ in $(seq 120); do
  state=$(sinfo -h -n "$host" -o '%T' 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || fail "the node did not come up idle (sinfo says \"$state\")"
echo "slurm test: one-node Slurm up ($host, $(nproc) CPUs, ports $ctld_port/$slurmd_port) in $(($(date +%s) - t_start)) s"

# Waits until Slurm's queue is empty (the array, then the merge it submits), at most 5 minutes.
wait_for_empty_queue() {
  for _ in $(seq 600); do
    [ -z "$(squeue -h -o '%i' 2>/dev/null)" ] && return 0
    sleep 0.5
  done
  squeue
  fail "Slurm's queue did not empty within 5 minutes"
}

# The study: participants 1-4 of seed 004, one per array task, then the merge. Task 3 fails the
# first time: its part file already holds another run (seed 2), which `experiment run` refuses.
out="$work/study dir/all.csv"
parts="$work/study dir/all.slurm/parts"
cd "$work"
submit=$("$exe" experiment slurm "$protocol" --participants sim:1-4 --per-task 1 --seed 1 --no-traces -o "$out" --time 0:10:00)
"$exe" experiment run "$protocol" --participants sim:3-3 --seed 2 --no-traces -o "$parts/p0003-0003.csv" 2>/dev/null
eval "$submit"   # the one command experiment slurm printed
wait_for_empty_queue
[ ! -e "$out" ] || fail "the merge ran although task 3 failed"
grep -q "another seed" "$work/study dir/all.slurm/logs/task-3.out" || fail "task 3 did not fail as arranged"
echo "slurm test: task 3 failed, the merge was cancelled; resubmitting task 3 alone"
# The fix, then only the failed task again: it submits a new merge, the finished parts stay.
rm -f "$parts/p0003-0003.csv" "$parts/p0003-0003.csv.meta.json"
sbatch --array=3 "$work/study dir/all.slurm/array.sbatch"
wait_for_empty_queue
[ -f "$out.meta.json" ] || fail "the merge did not write $out"
"$exe" experiment run "$protocol" --participants sim:1-4 --seed 1 --no-traces -o "$work/one.csv"
cmp "$out" "$work/one.csv" || fail "the merged file differs from one run of the same participants"
n_parts=$(ls "$parts/"*.csv | wc -l)
[ "$n_parts" -eq 4 ] || fail "expected 4 part files, found $n_parts"
echo "slurm test: 4 array tasks (one of them submitted again) and the merge gave the bytes of one run ($(wc -l <"$out") lines) in $(($(date +%s) - t_start)) s"
