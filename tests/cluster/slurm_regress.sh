#!/usr/bin/env bash
# The regression suite on a real scheduler: a single-node Slurm cluster started on this machine
# (munged with its own key, slurmctld and slurmd on loopback, every file in a temporary folder,
# no systemd), then docs/regression.md's Slurm recipe submitted as written there (its blocks
# `id slurm-job`, saved as regress.sh, and `id slurm-submit`, run by bash): a job array of four
# tasks, each running `occsim regress` on its shard from SLURM_ARRAY_TASK_ID, and the merge as a
# --wrap job after it, which Slurm runs under /bin/sh (dash on Debian). The merged report is
# compared check for check with a one-machine run of the same scenarios.
#
# Usage: slurm_regress.sh OCCSIM_EXE SOURCE_DIR
# Installs slurm-wlm and munge when missing (scripts/setup.sh cluster: apt-get, as root). Every
# wait has a deadline, and the daemons are stopped on every exit path. ctest: label `cluster`.
set -euo pipefail

occsim=$(readlink -f "$1")
source_dir=$(readlink -f "$2")
scenarios=scenarios/small  # what the documented job runs
tasks=4
deadline_start=60     # seconds for the daemons to come up
deadline_job=900      # seconds for the whole job array

say() { echo "slurm_regress: $*"; }
fail() { echo "slurm_regress: FAIL: $*" >&2; exit 1; }

# Without root (or sudo) and without the packages the test cannot run here: skipped (77), said.
if ! bash "$source_dir/scripts/setup.sh" cluster; then
  echo "slurm_regress: SKIPPED: slurm-wlm and munge are missing and cannot be installed (not root)"
  exit 77
fi
for tool in munged slurmctld slurmd sbatch squeue sinfo scontrol; do
  command -v "$tool" >/dev/null || fail "$tool not found after scripts/setup.sh cluster"
done

work=$(mktemp -d /tmp/occsim-slurm.XXXXXX)
chmod 755 "$work"
pids=()
cleanup() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ $status -ne 0 ]; then
    for log in "$work"/log/*.log; do [ -f "$log" ] && { echo "== $log"; tail -n 20 "$log"; }; done
  fi
  rm -rf "$work"
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT TERM
mkdir -p "$work"/{munge,etc,log,spool/ctld,spool/d,results}

# Two free TCP ports on loopback for slurmctld and slurmd.
free_port() {
  local port
  for _ in $(seq 100); do
    port=$((20000 + RANDOM % 20000))
    if ! (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then echo "$port"; return; fi
  done
  fail "no free port found"
}
ctld_port=$(free_port)
slurmd_port=$(free_port)
[ "$ctld_port" != "$slurmd_port" ] || slurmd_port=$((ctld_port + 1))

# munge with a key of its own; munged insists that its folders are not writable by others, and
# clients need to pass through the socket's folder.
chmod 711 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munge_socket="$work/munge/munge.socket"
munged --force --foreground --socket="$munge_socket" --key-file="$work/munge/munge.key" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/log/munged.log" \
  --seed-file="$work/munge/munged.seed" > "$work/log/munged.out" 2>&1 &
pids+=($!)

node=$(hostname -s)
cpus=$(nproc)
user=$(id -un)
cat > "$work/etc/slurm.conf" <<EOF
ClusterName=occsimtest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$munge_socket
CredType=cred/munge
StateSaveLocation=$work/spool/ctld
SlurmdSpoolDir=$work/spool/d
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SlurmdTimeout=60
InactiveLimit=0
KillWait=5
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=60 State=UP
EOF
export SLURM_CONF="$work/etc/slurm.conf"

# Wait until `munge -n | unmunge` works against our socket.
for i in $(seq "$deadline_start"); do
  if munge --socket="$munge_socket" -n 2>/dev/null | unmunge --socket="$munge_socket" >/dev/null 2>&1; then break; fi
  [ "$i" -lt "$deadline_start" ] || fail "munged did not answer within ${deadline_start}s"
  sleep 1
done
say "munged up"

slurmctld -D -i -f "$SLURM_CONF" > "$work/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$node" > "$work/log/slurmd.out" 2>&1 &
pids+=($!)
for i in $(seq "$deadline_start"); do
  state=$(timeout 10 sinfo -h -N -o %T 2>/dev/null | head -n 1 || true)
  case "$state" in idle*|mix*|alloc*) break ;; esac
  [ "$i" -lt "$deadline_start" ] || fail "the node did not become idle within ${deadline_start}s (state '$state')"
  sleep 1
done
say "slurm up: node $node idle, controller on 127.0.0.1:$ctld_port"

# The block of docs/regression.md under the marker naming `id NAME`, as written there.
doc_block() {
  awk -v id="id $1" '
    index($0, "<!-- runnable") == 1 && index($0, id) > 0 { found = 1; next }
    found && /^```/ { if (inside) exit; inside = 1; next }
    inside { print }' "$source_dir/docs/regression.md"
}
# The folder the recipe runs in, as a checkout would look to it: the built occsim at
# ./build/release/sim/occsim and the scenarios.
run="$work/run"
mkdir -p "$run/build/release/sim"
ln -s "$occsim" "$run/build/release/sim/occsim"
ln -s "$source_dir/scenarios" "$run/scenarios"
doc_block slurm-job > "$run/regress.sh"
doc_block slurm-submit > "$work/submit.sh"
grep -q "^#SBATCH --array=0-$((tasks - 1))" "$run/regress.sh" ||
  fail "docs/regression.md: no job script with #SBATCH --array=0-$((tasks - 1)) under id slurm-job"
grep -q -- "--wrap" "$work/submit.sh" || fail "docs/regression.md: no sbatch --wrap under id slurm-submit"
say "submitting docs/regression.md's recipe as written:"
cat "$work/submit.sh"
(cd "$run" && timeout 60 bash "$work/submit.sh") || fail "the documented submit commands failed"
start=$SECONDS
while [ -n "$(timeout 10 squeue -h -o %i 2>/dev/null || echo unknown)" ]; do
  if [ $((SECONDS - start)) -gt "$deadline_job" ]; then
    timeout 10 scancel --user="$user" || true
    fail "the jobs did not finish within ${deadline_job}s"
  fi
  sleep 2
done
say "jobs finished after $((SECONDS - start))s"
for out in "$run"/slurm-*.out; do
  [ -f "$out" ] || fail "the jobs left no output (slurm-*.out)"
  grep "^regress:" "$out" || true
done
if [ ! -f "$run/results/merged/checks.tsv" ]; then
  for out in "$run"/slurm-*.out; do echo "== $out"; tail -n 20 "$out"; done
  fail "the documented --wrap merge left no results/merged/checks.tsv (output above)"
fi
[ -n "$(ls "$run/history")" ] || fail "the documented merge wrote no history entry"

# The same scenarios on one machine, outside Slurm.
(cd "$run" && "$occsim" regress "$scenarios" --out "$work/single" >/dev/null)
(cd "$run" && "$occsim" merge "$work/single" --out "$work/single-merged" >/dev/null)

# Check for check: every row the same, except what a timing check measured (its name and
# verdict are compared, its milliseconds cannot be).
rows() { awk -F'\t' 'BEGIN { OFS = "\t" } $2 ~ /^frame time / { $3 = "-"; $4 = "-"; $5 = "-" } { print }' "$1"; }
if ! diff <(rows "$work/single-merged/checks.tsv") <(rows "$run/results/merged/checks.tsv"); then
  fail "the merged report of the job array differs from the one-machine run (diff above)"
fi
say "merged report of $tasks shards = one-machine run: $(($(wc -l < "$run/results/merged/checks.tsv") - 1)) checks"
