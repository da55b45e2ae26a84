#!/usr/bin/env bash
# test-one-node.sh: make test-farm. Starts a Slurm cluster of one node on this machine, all of it in a
# temporary folder (munged with a key made there, slurmctld and slurmd on localhost with a generated
# slurm.conf, as the current user), renders chapter 13's picture on it as a job array of tiles
# (tools/farm/farm.sh), joins them and checks that the picture is byte for byte the one this machine
# renders alone (and, where chapter 16 is built, that its frames rendered as a job array are the files
# one machine writes); then stops the daemons and removes the folder, also when a step fails. Needs Debian's
# slurm-wlm and munge (make test-farm installs them: tools/build/install-deps.sh farm).
# Exit status: 0 the pictures are identical, 1 not, or a step failed (its log is printed).
set -u
repo=$(cd "$(dirname "$0")/../.." && pwd)
cd "$repo"
build=${WHITTED_BUILD:-build}
tile_size=(128 96) # 4 x 4 tiles of chapter 13's 400 x 300 picture, whole 32 x 32 blocks, smaller at the edges
frames=3           # chapter 16's animation, where it is built: 3 frames of 160 x 100 pixels

for tool in munged slurmctld slurmd sbatch sinfo; do
    command -v "$tool" >/dev/null || { echo "test-farm: $tool is missing (tools/build/install-deps.sh farm)" >&2; exit 1; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/whitted-farm.XXXXXX") || exit 1
chmod 755 "$work" # munged refuses a socket in a folder others cannot enter

stop() { # every daemon started here, by its pid file, then the folder
    local pidfile
    for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid"; do
        [ -s "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null
    done
    [ -S "$work/socket/munge.socket" ] && munged --stop --socket="$work/socket/munge.socket" >/dev/null 2>&1
    sleep 1
    rm -rf "$work"
}
trap stop EXIT
trap 'exit 1' INT TERM

fail() { # fail WHAT: says what failed, prints the daemons' logs, and exits (stop runs)
    echo "test-farm: FAILED: $1" >&2
    local log
    for log in "$work"/log/*.log "$work"/farm/logs/*.log; do
        [ -s "$log" ] && { echo "---- $log" >&2; tail -n 20 "$log" >&2; }
    done
    exit 1
}

# munge: a key of 1024 random bytes, readable by its owner alone, and a socket of this folder's.
mkdir -p "$work/munge" "$work/socket" "$work/log" "$work/state" "$work/spool" "$work/one-machine"
chmod 700 "$work/munge"
head -c 1024 /dev/urandom >"$work/munge/munge.key" && chmod 400 "$work/munge/munge.key"
munged --force --key-file="$work/munge/munge.key" --socket="$work/socket/munge.socket" \
    --pid-file="$work/munge/munged.pid" --log-file="$work/log/munged.log" --seed-file="$work/munge/seed" ||
    fail "munged did not start"

# Two free ports for the controller and the node daemon.
port_free() { ! ss -Htln "sport = :$1" 2>/dev/null | grep -q .; }
port=$((20000 + $$ % 20000 * 2))
while ! port_free "$port" || ! port_free $((port + 1)); do port=$((port + 2)); done

user=$(id -un) host=$(hostname -s) cpus=$(nproc)
export SLURM_CONF="$work/slurm.conf"
cat >"$SLURM_CONF" <<CONF
ClusterName=whitted
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$work/socket/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
NodeName=whitted1 NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$cpus State=UNKNOWN
PartitionName=farm Nodes=whitted1 Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
slurmd -f "$SLURM_CONF" -N whitted1 || fail "slurmd did not start"
for ((second = 0; second < 30; second++)); do
    [ "$(sinfo -h -n whitted1 -o %t 2>/dev/null)" = idle ] && break
    sleep 1
done
[ "$(sinfo -h -n whitted1 -o %t 2>/dev/null)" = idle ] || fail "the node did not come up in 30 s: $(sinfo 2>&1)"
echo "test-farm: a one-node Slurm cluster is up in $work (ports $port and $((port + 1)))"

# The picture on this machine alone, and as a job array of tiles on the cluster.
started=$(date +%s.%N)
"$build/chapter-13" --quiet -o "$work/one-machine.png" || fail "chapter 13 did not render"
alone=$(date +%s.%N)
tools/farm/farm.sh --tile-size "${tile_size[@]}" --dir "$work/farm" -o "$work/farm.png" -- \
    "$build/chapter-13" || fail "farm.sh"
farmed=$(date +%s.%N)
cmp "$work/one-machine.png" "$work/farm.png" || fail "the farm's picture differs from the one machine's"
tiles=$(ls "$work"/farm/tile-*.png | wc -l)
awk -v tiles="$tiles" -v farm="$(awk -v a="$alone" -v b="$farmed" 'BEGIN { print b - a }')" \
    -v alone="$(awk -v a="$started" -v b="$alone" 'BEGIN { print b - a }')" 'BEGIN {
    printf "test-farm: passed: %d tiles rendered by a Slurm job array (%.1f s from submitting to joining) ", tiles, farm
    printf "joined into the very picture one machine renders alone (%.1f s)\n", alone }'

# Chapter 16's animation, where it is built: its frames as a job array, each the file one machine writes.
if [ -x "$build/chapter-16" ]; then
    size=(--width 160 --height 100)
    "$build/chapter-16" --quiet "${size[@]}" --frames "$frames" -o "$work/one-machine/frame.png" ||
        fail "chapter 16 did not render its frames"
    tools/farm/farm.sh --frames "$frames" --dir "$work/frames" -- "$build/chapter-16" "${size[@]}" ||
        fail "farm.sh --frames"
    for ((k = 1; k <= frames; k++)); do
        name=$(printf 'frame-%04d.png' "$k")
        cmp "$work/one-machine/$name" "$work/frames/$name" || fail "the farm's $name differs from the one machine's"
    done
    echo "test-farm: passed: chapter 16's $frames frames rendered by a Slurm job array are the files one machine writes"
fi
