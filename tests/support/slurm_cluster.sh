#!/usr/bin/env bash
# Start/stop a throw-away one-node Slurm cluster (munged + slurmctld + slurmd) whose
# state, config, sockets, logs and pid files all live under one scratch DIR.
#
#   slurm_cluster.sh start DIR   # DIR: absolute, existing scratch folder
#   slurm_cluster.sh stop  DIR   # idempotent
#
# Clients then need only:  export SLURM_CONF=DIR/slurm.conf
# Needs (Debian bookworm): slurmctld slurmd slurm-client munge. Run as root. No systemd.
set -euo pipefail

WAIT_IDLE_SECS=${SLURM_KIT_WAIT_SECS:-60}   # bound on "node becomes idle"
STOP_WAIT_SECS=20                            # bound on each daemon's exit after SIGTERM

die() { echo "slurm_cluster.sh: $*" >&2; exit 1; }

usage() { die "usage: $0 start|stop DIR (DIR absolute)"; }

[[ $# -eq 2 ]] || usage
CMD=$1
DIR=$2
[[ $DIR == /* ]] || usage
[[ $DIR != *[[:space:]]* ]] || die "DIR must not contain whitespace (slurm.conf paths): $DIR"
[[ -d $DIR ]] || die "DIR $DIR does not exist"
DIR=$(cd "$DIR" && pwd -P)   # resolve symlinks so paths in slurm.conf are stable

MUNGE_DIR=$DIR/munge          # key, socket, pid, log (0700: munged --force accepts it)
MUNGE_SOCK=$MUNGE_DIR/munge.socket
CONF=$DIR/slurm.conf
# pid file -> expected process name (checked so a recycled pid is never killed)
DAEMONS=(slurmd slurmctld munged)  # stop order: node daemon first, munge last

pidfile_of() {
    case $1 in
        munged) echo "$MUNGE_DIR/munged.pid" ;;
        slurmctld) echo "$DIR/run/slurmctld.pid" ;;
        slurmd) echo "$DIR/run/slurmd.pid" ;;
    esac
}

# Print the pid from NAME's pid file if that pid is alive and really is NAME.
live_pid() {
    local name=$1 pf pid comm
    pf=$(pidfile_of "$name")
    [[ -s $pf ]] || return 1
    pid=$(tr -dc '0-9' <"$pf")
    [[ -n $pid ]] || return 1
    comm=$(cat "/proc/$pid/comm" 2>/dev/null) || return 1
    [[ $comm == "$name" ]] || return 1
    alive "$pid" || return 1
    echo "$pid"
}

# True if pid exists and is not a zombie (an unreaped zombie has already exited).
alive() {
    local st
    st=$(awk '{sub(/^.*\) /, ""); print $1}' "/proc/$1/stat" 2>/dev/null) || return 1
    [[ -n $st && $st != Z ]]
}

# Is TCP port $1 in LISTEN state anywhere (IPv4 or IPv6)? Reads /proc: no ss/netstat needed.
port_in_use() {
    local hex
    hex=$(printf '%04X' "$1")
    awk -v p=":$hex" '$4=="0A" && substr($2, length($2)-4)==p {found=1} END {exit !found}' \
        /proc/net/tcp /proc/net/tcp6 2>/dev/null
}

# First pair of consecutive free ports starting at $1.
free_port_pair() {
    local p=$1
    while ((p < 65000)); do
        if ! port_in_use "$p" && ! port_in_use $((p + 1)); then echo "$p"; return 0; fi
        p=$((p + 2))
    done
    die "no free port pair found"
}

dump_logs() {
    local f
    for f in "$MUNGE_DIR/munged.log" "$DIR/log/slurmctld.log" "$DIR/log/slurmd.log" \
             "$DIR/log/slurmctld.stdio" "$DIR/log/slurmd.stdio"; do
        [[ -s $f ]] || continue
        echo "===== $f (last 60 lines) =====" >&2
        tail -n 60 "$f" >&2
    done
}

# All descendants of the given pids (from one ps snapshot).
descendants() {
    ps -eo pid=,ppid= | awk -v roots=" $* " '
        { parent[$1] = $2; pids[NR] = $1 }
        END {
            n = split(roots, r, " "); for (i = 1; i <= n; i++) inset[r[i]] = 1
            do { changed = 0
                 for (k in pids) { p = pids[k]
                     if (!(p in inset) && (parent[p] in inset)) { inset[p] = 1; out[p] = 1; changed = 1 } }
            } while (changed)
            for (p in out) print p
        }'
}

do_stop() {
    local name pid i any=0
    # Cancel jobs first so slurmd reaps their slurmstepd processes before it exits.
    if live_pid slurmctld >/dev/null && [[ -f $CONF ]]; then
        SLURM_CONF=$CONF timeout 5 scancel --quiet --user=root 2>/dev/null || true
        for ((i = 0; i < 20; i++)); do
            [[ -z $(SLURM_CONF=$CONF timeout 5 squeue -h -t R,CG -o %i 2>/dev/null) ]] && break
            sleep 0.5
        done
    fi
    for name in "${DAEMONS[@]}"; do
        pid=$(live_pid "$name") || continue
        any=1
        kill -TERM "$pid" 2>/dev/null || true
        for ((i = 0; i < STOP_WAIT_SECS * 10; i++)); do
            alive "$pid" || break
            sleep 0.1
        done
        if alive "$pid"; then
            echo "slurm_cluster.sh: $name ($pid) ignored SIGTERM, sending SIGKILL" >&2
            kill -KILL "$pid" 2>/dev/null || true
            sleep 0.2
        fi
    done
    # Stray job steps of THIS cluster (slurmd sets SLURM_CONF=$CONF in slurmstepd's
    # environment) and everything below them: only left if slurmctld/slurmd died early.
    local stray=()
    for pid in $(pgrep -x slurmstepd || true); do
        if tr '\0' '\n' 2>/dev/null <"/proc/$pid/environ" | grep -qxF "SLURM_CONF=$CONF"; then
            stray+=("$pid")
        fi
    done
    if ((${#stray[@]})); then
        echo "slurm_cluster.sh: killing stray slurmstepd ${stray[*]} and their children" >&2
        # shellcheck disable=SC2046
        kill -KILL $(descendants "${stray[@]}") "${stray[@]}" 2>/dev/null || true
    fi
    rm -f "$(pidfile_of munged)" "$(pidfile_of slurmctld)" "$(pidfile_of slurmd)"
    if ((any)); then echo "slurm_cluster.sh: stopped cluster in $DIR"; fi
    return 0
}

write_conf() {
    local host=$1 cpus=$2 mem_mb=$3 ctld_port=$4 slurmd_port=$5
    cat >"$CONF" <<EOF
# Generated by slurm_cluster.sh: one-node test cluster, everything under $DIR
ClusterName=pcsimtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCK
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$(pidfile_of slurmctld)
SlurmdPidFile=$(pidfile_of slurmd)
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$DIR/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MailProg=/bin/true
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MaxArraySize=100001
MaxJobCount=200000
MinJobAge=4
InactiveLimit=0
KillWait=5
SlurmctldTimeout=30
SlurmdTimeout=60
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

do_start() {
    local name host cpus mem_kb mem_mb port i state
    [[ $(id -u) -eq 0 ]] || die "must run as root (SlurmUser=root, SlurmdUser=root)"
    for name in munged mungekey slurmctld slurmd sinfo scancel squeue; do
        command -v "$name" >/dev/null || die "$name not found: apt-get install -y slurmctld slurmd slurm-client munge"
    done
    for name in "${DAEMONS[@]}"; do
        if live_pid "$name" >/dev/null; then die "$name already running for $DIR; run stop first"; fi
    done
    # Unix socket paths are limited to 107 bytes.
    ((${#MUNGE_SOCK} < 100)) || die "DIR path too long for a unix socket: $DIR"

    mkdir -p "$MUNGE_DIR" "$DIR/state" "$DIR/spool" "$DIR/log" "$DIR/run"
    chmod 700 "$MUNGE_DIR"
    : >"$DIR/plugstack.conf"   # empty: keeps the system's /etc/slurm/plugstack.conf out of it

    host=$(hostname -s)
    cpus=$(nproc)
    mem_kb=$(awk '/^MemTotal:/ {print $2}' /proc/meminfo)
    mem_mb=$((mem_kb * 9 / 10 / 1024))   # a bit below the real size or slurmd drains the node
    port=$(free_port_pair "${SLURM_KIT_PORT:-16817}")
    write_conf "$host" "$cpus" "$mem_mb" "$port" $((port + 1))

    # Fresh key for this cluster only; the system /etc/munge/munge.key is never used.
    [[ -s $MUNGE_DIR/munge.key ]] || mungekey --create --bits=1024 --keyfile="$MUNGE_DIR/munge.key"
    chmod 600 "$MUNGE_DIR/munge.key"

    # If anything below fails, undo what was started.
    trap 'echo "slurm_cluster.sh: start failed" >&2; dump_logs; do_stop; exit 1' ERR

    # --force: DIR is usually 0700 and munged otherwise insists every socket ancestor is o+x.
    munged --force --socket="$MUNGE_SOCK" --key-file="$MUNGE_DIR/munge.key" \
        --pid-file="$(pidfile_of munged)" --log-file="$MUNGE_DIR/munged.log" \
        --seed-file="$MUNGE_DIR/munged.seed" </dev/null >/dev/null 2>&1
    for ((i = 0; i < 50; i++)); do [[ -S $MUNGE_SOCK ]] && break; sleep 0.1; done
    munge --socket="$MUNGE_SOCK" --no-input | unmunge --socket="$MUNGE_SOCK" >/dev/null

    # Daemonised (no -D); stdio to files so a caller's pipes are never held open.
    slurmctld -f "$CONF" -c -i </dev/null >"$DIR/log/slurmctld.stdio" 2>&1
    slurmd -f "$CONF" -N "$host" </dev/null >"$DIR/log/slurmd.stdio" 2>&1
    trap - ERR

    for ((i = 0; i < WAIT_IDLE_SECS * 2; i++)); do
        state=$(SLURM_CONF=$CONF timeout 5 sinfo -h -o %T 2>/dev/null || true)
        if [[ $state == idle ]]; then
            echo "slurm_cluster.sh: node $host idle (ports $port/$((port + 1))); for clients:"
            echo "export SLURM_CONF=$CONF"
            return 0
        fi
        for name in "${DAEMONS[@]}"; do
            live_pid "$name" >/dev/null || { echo "slurm_cluster.sh: $name died" >&2; i=1000000; }
        done
        sleep 0.5
    done
    echo "slurm_cluster.sh: node not idle within ${WAIT_IDLE_SECS}s (sinfo state: '${state:-none}')" >&2
    dump_logs
    do_stop
    exit 1
}

case $CMD in
    start) do_start ;;
    stop) do_stop ;;
    *) usage ;;
esac
