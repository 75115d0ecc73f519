#!/usr/bin/env bash
# Integration test of tools/cluster/slurm_array.sh on a real, single-node Slurm: starts munged,
# slurmctld and slurmd from Debian's packages on localhost, with every file (munge key,
# slurm.conf, state, logs) in a fresh temporary folder and free ports; runs a 4-shard array over
# bundled scenarios and checks the merged result equals a local `rts test` run case by case
# (status and state hash), then stops the daemons. Exit 77 (CTest's SKIP_RETURN_CODE) when
# Slurm or munge is not installed: `tools/setup.sh --cluster` installs them.
#
#   tests/cluster/slurm_test.sh RTS SOURCE_DIR
set -euo pipefail

rts="$1"
src="$2"
for tool in munged slurmctld slurmd sbatch sinfo scontrol; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool not found; tools/setup.sh --cluster installs Slurm and munge"
    exit 77
  fi
done

tmp=$(mktemp -d /tmp/warpath-slurm.XXXXXX)
chmod 755 "$tmp"  # munged wants its socket's folders searchable by all
user=$(id -un)
export SLURM_CONF="$tmp/slurm.conf"
munge_pid=""

cleanup() {
  local status=$?
  scontrol shutdown >/dev/null 2>&1 || true
  for pidfile in "$tmp/slurmd.pid" "$tmp/slurmctld.pid"; do
    for _ in $(seq 50); do
      [[ -f "$pidfile" ]] && kill -0 "$(cat "$pidfile")" 2>/dev/null || break
      sleep 0.1
    done
  done
  [[ -n "$munge_pid" ]] && kill "$munge_pid" 2>/dev/null || true
  if ((status != 0)); then
    echo "--- logs ($tmp) ---"
    tail -n 30 "$tmp"/log/*.log "$tmp"/cluster/logs/*.out 2>/dev/null || true
  else
    rm -rf "$tmp"
  fi
}
trap cleanup EXIT

# A port the kernel hands out as free (python3), else a random high one.
free_port() {
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])' \
    2>/dev/null || echo $((20000 + RANDOM % 20000))
}

mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/log"
chmod 700 "$tmp/munge"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge/munge.key"
# --force: munged refuses a socket under /tmp (and root) without it.
munged --force --socket="$tmp/munge/munge.sock" --key-file="$tmp/munge/munge.key" \
  --log-file="$tmp/log/munged.log" --pid-file="$tmp/munge/munged.pid" \
  --seed-file="$tmp/munge/munged.seed"
munge_pid=$(cat "$tmp/munge/munged.pid")

ctld_port=$(free_port)
slurmd_port=$(free_port)
while [[ "$slurmd_port" == "$ctld_port" ]]; do slurmd_port=$(free_port); done
cat >"$SLURM_CONF" <<CONF
ClusterName=warpath
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
AuthInfo=socket=$tmp/munge/munge.sock
CredType=cred/munge
SlurmUser=$user
SlurmdUser=$user
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
PlugStackConfig=$tmp/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 NodeHostname=$(hostname) CPUs=$(nproc) State=UNKNOWN
PartitionName=warpath Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
touch "$tmp/plugstack.conf"
slurmctld -i
slurmd -N localhost

for i in $(seq 100); do
  state=$(sinfo -h -o %T 2>/dev/null || true)
  [[ "$state" == idle* ]] && break
  ((i < 100)) || { echo "FAIL: the node did not come up (state '$state')"; exit 1; }
  sleep 0.3
done
echo "slurm up: node $(sinfo -h -o '%N %T %c')"

# The bundled scenarios but the 2,000-unit one (30 s alone), at four seeds: 44 cases.
scenarios=()
for f in "$src"/scenarios/*.yaml; do
  [[ "$(basename "$f")" == stress_2000.yaml ]] || scenarios+=("$f")
done
test_args=("${scenarios[@]}" --seeds 1..4)

local_status=0
"$rts" test "${test_args[@]}" --jobs 2 --report-dir "$tmp/local" >"$tmp/local.out" || local_status=$?
cluster_status=0
bash "$src/tools/cluster/slurm_array.sh" --shards 4 --out "$tmp/cluster" --rts "$rts" --wait \
  --cpus 1 --sbatch-arg --time=10 -- "${test_args[@]}" >"$tmp/cluster.out" || cluster_status=$?
cat "$tmp/cluster.out"

fail() { echo "FAIL: $*"; exit 1; }
((local_status == cluster_status)) ||
  fail "the local run exited $local_status, the merged cluster run $cluster_status"
for k in 0 1 2 3; do
  [[ -f "$tmp/cluster/shard-$k/summary.json" ]] || fail "shard $k wrote no summary"
  [[ -f "$tmp/cluster/shard-$k/junit.xml" ]] || fail "shard $k wrote no JUnit"
done
[[ -f "$tmp/cluster/merged/junit.xml" ]] || fail "the merge wrote no JUnit"
# Case by case, in order: name, seed, status and state hash (summary.json puts a key a line).
cases() { grep -E '^ *"(name|seed|state_hash|status)":' "$1"; }
diff <(cases "$tmp/local/summary.json") <(cases "$tmp/cluster/merged/summary.json") ||
  fail "the merged shards differ from the local run"
[[ $(cases "$tmp/local/summary.json" | grep -c '"state_hash": "') == 44 ]] ||
  fail "expected 44 cases with a state hash"
# The console lines too, but for the wall time of each case.
strip() { sed -E 's/, [0-9.]+ s\)$/)/' "$1"; }
diff <(strip "$tmp/local.out") <(strip "$tmp/cluster/logs/merge.out") ||
  fail "the merge printed other results than the local run"
for k in 0 1 2 3; do
  n=$(grep -c '"state_hash": "' "$tmp/cluster/shard-$k/summary.json" || true)
  echo "shard $k: $n cases"
done
echo "PASS: 4 shards on Slurm reproduce the local run (44 cases, same states and hashes)"
