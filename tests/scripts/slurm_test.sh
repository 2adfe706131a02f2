#!/usr/bin/env bash
# docs/cluster.md's cluster path on a real Slurm: a single-node Slurm (munged, slurmctld, slurmd from
# Debian's packages, on 127.0.0.1, its configuration, key, state and logs in a scratch
# directory) runs docs/cluster.md's job array as written; then
#   1. the array is submitted held, one task cancelled (scancel JOB_2), the rest released;
#   2. docs/cluster.md's merge names the missing shard (exit 2, "shard 2 of 16 ... is missing");
#   3. the cancelled task is rerun alone (sbatch --array=2 job.sh, as docs/cluster.md says);
#   4. docs/cluster.md's merge block (merge, figures) succeeds, and the merged reports verify against
#      a single-machine run of the study at --rtol 0 (nsbench-study STUDY --verify reports).
# The job script and the merge block are read from docs/cluster.md (scripts/doc-commands.py
# --block) and run as written but for two things: the study (docs/cluster.md's `all --full`, hours of
# work) is replaced by $STUDY, and `--cpus-per-task=1` is given to sbatch (it overrides the
# script's #SBATCH line) so that the tasks fit this machine's cores.
#
#   slurm_test.sh BUILD_DIR SOURCE_DIR
#
# Exit 77 (CTest: skipped), saying why, where Slurm or munge is not installed
# (scripts/install-deps.sh tests installs them) or when not root (slurmd must be). Every wait
# has a timeout; the daemons are stopped on any exit (trap). Prints the round trip's times.
set -euo pipefail
build="$(cd "$1" && pwd)"
source_dir="$(cd "$2" && pwd)"
STUDY="${STUDY:-hard}"  # short, and its runs end in every outcome (ok, diverged, energy blow-up, penetration, over budget, n/a)
WAIT_SECONDS="${WAIT_SECONDS:-300}"  # the longest any one wait may take

for program in munged mungekey slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
  if ! command -v "$program" > /dev/null && [ ! -x "/usr/sbin/$program" ]; then
    echo "SKIPPED: $program is not installed (Slurm and munge: scripts/install-deps.sh tests installs" \
         "slurmctld, slurmd, slurm-client and munge)"
    exit 77
  fi
done
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIPPED: not root (slurmd runs jobs as their user and must be started as root)"
  exit 77
fi
export PATH="$PATH:/usr/sbin"

work="$(mktemp -d /tmp/nsbench-slurm.XXXXXX)"
chmod 711 "$work"  # munged: the socket's directory must be searchable by all
cleanup() {
  local status=$?
  for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munged.pid"; do
    [ -s "$pidfile" ] || continue
    local pid
    pid="$(cat "$pidfile")"
    kill "$pid" 2> /dev/null || continue
    for _ in $(seq 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2> /dev/null || true
  done
  if [ "$status" -ne 0 ] && [ "$status" -ne 77 ]; then
    for log in "$work"/*.log; do echo "--- $log (last lines)"; tail -n 20 "$log"; done
  fi
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# wait_for SECONDS WHAT COMMAND...: until COMMAND succeeds, at most SECONDS.
wait_for() {
  local seconds="$1" what="$2"
  shift 2
  local deadline=$((SECONDS + seconds))
  until "$@"; do
    [ "$SECONDS" -lt "$deadline" ] || fail "timed out after ${seconds} s waiting for $what"
    sleep 0.5
  done
}

# Two free TCP ports on the loopback for slurmctld and slurmd.
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
host="$(hostname -s)"

mungekey --create --keyfile="$work/munge.key" --bits=1024
munged --force --key-file="$work/munge.key" --socket="$work/munge.socket" --pid-file="$work/munged.pid" \
       --log-file="$work/munged.log" --seed-file="$work/munged.seed"
mkdir -p "$work/state" "$work/spool"
cat > "$work/slurm.conf" << EOF
ClusterName=nsbench-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=nsbench Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$work/slurm.conf"
SECONDS=0
slurmctld -i
slurmd
node_idle() { [ "$(sinfo -h -n "$host" -o %t 2> /dev/null)" = idle ]; }
wait_for 60 "the node to be idle" node_idle
echo "slurm: single-node Slurm up in ${SECONDS} s (slurmctld :$ctld_port, slurmd :$slurmd_port)"

# A checkout-like directory to submit from: docs/cluster.md's paths are relative to the checkout.
checkout="$work/checkout"
mkdir -p "$checkout"
ln -s "$build" "$checkout/build"
ln -s "$source_dir/scripts" "$checkout/scripts"
readme_block() {  # NAME: docs/cluster.md's block, the study replaced (and that replacement checked)
  local text
  text="$(/usr/bin/python3 "$source_dir/scripts/doc-commands.py" "$source_dir/docs/cluster.md" --block "$1")"
  grep -q -- 'nsbench-study all --full ' <<< "$text" || fail "docs/cluster.md's block $1 no longer runs 'nsbench-study all --full'"
  sed "s/nsbench-study all --full /nsbench-study $STUDY /" <<< "$text"
}
readme_block slurm-job > "$checkout/job.sh"
readme_block slurm-merge > "$checkout/merge.sh"
shards="$(sed -n 's/^#SBATCH .*--array=1-\([0-9]*\).*/\1/p' "$checkout/job.sh")"
[ -n "$shards" ] || fail "docs/cluster.md's job script has no '#SBATCH ... --array=1-N' line"
grep -q -- "--shard \${SLURM_ARRAY_TASK_ID}/$shards " "$checkout/job.sh" ||
  fail "docs/cluster.md's job script does not shard into its array's $shards tasks"
echo "slurm: docs/cluster.md's job script, study $STUDY, $shards tasks:"
sed 's/^/    /' "$checkout/job.sh"

job_done() { [ -z "$(squeue -h -j "$1" 2> /dev/null)" ]; }
cd "$checkout"

# 1. Held, task 2 cancelled, the rest released.
t0=$SECONDS
job="$(sbatch --parsable --hold --cpus-per-task=1 job.sh)"
scancel "${job}_2"
scontrol release "$job"
wait_for "$WAIT_SECONDS" "array job $job to finish" job_done "$job"
array_seconds=$((SECONDS - t0))
for i in $(seq "$shards"); do
  f="reports/shards/$STUDY-$i-of-$shards.json"
  if [ "$i" -eq 2 ]; then
    [ ! -e "$f" ] || fail "the cancelled task 2 wrote $f"
  else
    [ -s "$f" ] || { cat slurm-*.out >&2 || true; fail "task $i wrote no $f"; }
  fi
done

# 2. The merge names the missing shard.
set +e
bash -euo pipefail merge.sh > merge-missing.log 2>&1
status=$?
set -e
[ "$status" -eq 2 ] || { cat merge-missing.log >&2; fail "merge with shard 2 missing exited $status, expected 2"; }
grep -q "shard 2 of $shards of study $STUDY is missing" merge-missing.log ||
  { cat merge-missing.log >&2; fail "the merge did not name the missing shard 2"; }
echo "slurm: merge without task 2: $(grep -m1 'missing' merge-missing.log)"

# 3. The cancelled task rerun alone.
t0=$SECONDS
rerun="$(sbatch --parsable --array=2 --cpus-per-task=1 job.sh)"
wait_for "$WAIT_SECONDS" "rerun job $rerun to finish" job_done "$rerun"
rerun_seconds=$((SECONDS - t0))
[ -s "reports/shards/$STUDY-2-of-$shards.json" ] || { cat slurm-*.out >&2 || true; fail "the rerun wrote no shard 2"; }

# 4. Merge (docs/cluster.md's block: merge, figures), then the merged reports against one machine's run.
t0=$SECONDS
timeout "$WAIT_SECONDS" bash -euo pipefail merge.sh > merge.log 2>&1 || { cat merge.log >&2; fail "docs/cluster.md's merge failed"; }
merge_seconds=$((SECONDS - t0))
timeout "$WAIT_SECONDS" build/studies/nsbench-study "$STUDY" --verify reports --rtol 0 > verify.log 2>&1 ||
  { cat verify.log >&2; fail "the merged reports differ from a single-machine run"; }
echo "slurm: $(tail -n 1 verify.log)"
echo "slurm: round trip ${SECONDS} s: array of $shards tasks (one cancelled) ${array_seconds} s, rerun ${rerun_seconds} s," \
     "merge and figures ${merge_seconds} s, then the single-machine verify"
