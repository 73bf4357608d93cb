#!/usr/bin/env bash
# A single-node SLURM cluster on localhost (Debian's slurm-wlm and munge), for the
# integration test tests/workflow/test_slurm.py and for trying profiles/slurm without a cluster.
#
#   tools/slurm/localhost_slurm.sh install   # apt-get the packages (root)
#   tools/slurm/localhost_slurm.sh start     # munged, slurmctld, slurmd; waits for the node
#   tools/slurm/localhost_slurm.sh check     # sbatch --wrap hostname, waits for completion
#   tools/slurm/localhost_slurm.sh status    # which daemons run (exit 3 when not all)
#   tools/slurm/localhost_slurm.sh env       # prints `export SLURM_CONF=... PATH=...`
#   tools/slurm/localhost_slurm.sh stop      # cancels jobs, stops the daemons by their PIDs
#
# Every file (config, MUNGE key and socket, state, spool, logs, PIDs) lives in the run
# directory $TENNIS_STROKE_SLURM_DIR (default /tmp/tennis-stroke-slurm); nothing under /etc
# is written.  The daemons read the generated config with -f; clients (sbatch, squeue,
# Snakemake's plugin) need SLURM_CONF pointing at it and the run directory's bin/ first in
# PATH (an srun wrapper, see write_srun_wrapper), and jobs inherit both:
#   eval "$(tools/slurm/localhost_slurm.sh env)"
# start and stop are idempotent.  Errors are one line on stderr, naming the log to read.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# The daemons and mungekey live in sbin, which a user's PATH often lacks.
PATH="$PATH:/usr/sbin:/sbin"
RUN_DIR="${TENNIS_STROKE_SLURM_DIR:-/tmp/tennis-stroke-slurm}"
START_TIMEOUT_S="${TENNIS_STROKE_SLURM_START_TIMEOUT:-60}"
# Non-default ports, so that a system SLURM on this machine cannot clash with ours.
CTLD_PORT="${TENNIS_STROKE_SLURMCTLD_PORT:-16817}"
SLURMD_PORT="${TENNIS_STROKE_SLURMD_PORT:-16818}"
PACKAGES=(slurmctld slurmd slurm-client munge)
# Stop order: the node daemon first, MUNGE (which the others authenticate with) last.
DAEMONS=(slurmd slurmctld munged)

export SLURM_CONF="$RUN_DIR/etc/slurm.conf"
MUNGE_SOCKET="$RUN_DIR/munge-socket/munged.socket"

die() {
    echo "localhost_slurm.sh: $*" >&2
    exit 1
}

installed() {
    local tool
    for tool in munged mungekey slurmctld slurmd sbatch sinfo squeue scancel; do
        command -v "$tool" >/dev/null || return 1
    done
}

pid_of() {  # PID of a daemon we started, if it is still alive; else nothing, status 1.
    local name="$1" pidfile="$RUN_DIR/pid/$1.pid" pid
    [[ -s "$pidfile" ]] || return 1
    pid="$(<"$pidfile")"
    # The PID file may be stale and its number reused: check the process is ours.
    [[ "$pid" =~ ^[0-9]+$ && "$(cat "/proc/$pid/comm" 2>/dev/null)" == "$name" ]] || return 1
    echo "$pid"
}

node_state() {  # the node's state as sinfo prints it (idle, mix, alloc, down*, ...)
    timeout 10 sinfo --noheader --Node --nodes=localhost --format=%t 2>/dev/null || true
}

cmd_install() {
    if installed; then
        echo "SLURM and MUNGE already installed"
        return
    fi
    [[ "$(id -u)" == 0 ]] || die "install needs root (apt-get): run it as root or with sudo"
    command -v apt-get >/dev/null ||
        die "no apt-get: install ${PACKAGES[*]} with your package manager"
    local log="${TMPDIR:-/tmp}/tennis-stroke-slurm-install.log"
    # --no-install-recommends: the daemons and clients only (seconds, no MariaDB/slurmdbd).
    # In containers the packages' postinst cannot start the system services (policy-rc.d
    # denies it); on a systemd host it may start munge.service, which does not disturb
    # ours (own key, own socket).
    if ! {
        apt-get update &&
            DEBIAN_FRONTEND=noninteractive \
                apt-get install -y --no-install-recommends "${PACKAGES[@]}"
    } >"$log" 2>&1; then
        die "apt-get install ${PACKAGES[*]} failed: see $log"
    fi
    installed || die "apt-get ran but a SLURM or MUNGE command is still missing: see $log"
    echo "installed ${PACKAGES[*]}"
}

write_config() {
    # `slurmd -C` prints this machine's node line: CPUs, Boards, SocketsPerBoard,
    # CoresPerSocket, ThreadsPerCore, RealMemory (MiB).  Keep all but the name, and
    # configure 95% of the memory: a node that registers with less memory than its
    # configured RealMemory is drained, and the reading can vary slightly between runs.
    local line hardware="" field memory
    line="$(slurmd -C | head -n 1)" ||
        die "slurmd -C failed: cannot read this machine's CPUs and memory"
    for field in $line; do
        case "$field" in
            NodeName=*) ;;
            RealMemory=*)
                memory="${field#RealMemory=}"
                hardware+=" RealMemory=$((memory * 95 / 100))"
                ;;
            *) hardware+=" $field" ;;
        esac
    done
    [[ "$hardware" == *CPUs=*RealMemory=* ]] || die "unexpected output of slurmd -C: $line"
    sed -e "s|@RUN_DIR@|$RUN_DIR|g" \
        -e "s|@CTLD_PORT@|$CTLD_PORT|g" \
        -e "s|@SLURMD_PORT@|$SLURMD_PORT|g" \
        -e "s|@HARDWARE@|${hardware# }|g" \
        "$HERE/slurm.conf.in" >"$SLURM_CONF"
}

write_srun_wrapper() {
    # snakemake-executor-plugin-slurm-jobstep (0.6) starts each job's step with an srun
    # whose environment has every SLURM_* variable removed, SLURM_CONF included: that srun
    # then looks for /etc/slurm/slurm.conf, which we do not write.  A wrapper first in PATH
    # (PATH is kept) sets SLURM_CONF again.
    local real="" candidate
    for candidate in $(type -a -P srun); do  # the real srun, not an earlier wrapper
        if [[ "$candidate" != "$RUN_DIR/bin/srun" ]]; then
            real="$candidate"
            break
        fi
    done
    [[ -n "$real" ]] || die "srun not found: run tools/slurm/localhost_slurm.sh install (root)"
    mkdir -p "$RUN_DIR/bin"
    {
        echo '#!/bin/sh'
        echo '# Written by tools/slurm/localhost_slurm.sh (see write_srun_wrapper there).'
        printf 'export SLURM_CONF=%q\nexec %q "$@"\n' "$SLURM_CONF" "$real"
    } >"$RUN_DIR/bin/srun"
    chmod 755 "$RUN_DIR/bin/srun"
}

client_env() {  # the environment that clients (sbatch, squeue, Snakemake) need
    echo "export SLURM_CONF=$SLURM_CONF PATH=$RUN_DIR/bin:\$PATH"
}

wait_for() {  # wait_for SECONDS LOG COMMAND...: poll COMMAND until it succeeds
    local seconds="$1" log="$2" waited=0
    shift 2
    until "$@" >/dev/null; do
        ((waited < seconds * 2)) || die "not ready after ${seconds} s: read $log"
        sleep 0.5
        waited=$((waited + 1))
    done
}

alive_or_die() {  # fail early (instead of at the timeout) when a daemon has exited
    local name="$1" log="$2"
    pid_of "$name" >/dev/null || die "$name is not running: read $log"
}

node_idle() {
    alive_or_die slurmctld "$RUN_DIR/log/slurmctld.log"
    alive_or_die slurmd "$RUN_DIR/log/slurmd.log"
    [[ "$(node_state)" == idle ]]
}

all_running() {
    local name
    for name in "${DAEMONS[@]}"; do
        pid_of "$name" >/dev/null || return 1
    done
}

cmd_start() {
    installed || die "SLURM not installed: run tools/slurm/localhost_slurm.sh install (root)"
    # slurmd must be root to start job steps (as the job's user, with its limits).
    [[ "$(id -u)" == 0 ]] || die "start needs root (slurmd runs as root)"
    if all_running && [[ "$(node_state)" =~ ^(idle|mix|alloc)$ ]]; then
        echo "SLURM already running on localhost; clients need: $(client_env)"
        return
    fi
    cmd_stop >/dev/null  # a half-started cluster from an earlier run: start afresh
    # Root writes into this directory: refuse one that another user made (e.g. a symlink
    # planted in /tmp).
    if [[ -L "$RUN_DIR" ]] || [[ -e "$RUN_DIR" && ! -O "$RUN_DIR" ]]; then
        die "$RUN_DIR is a symlink or another user's: remove it or set TENNIS_STROKE_SLURM_DIR"
    fi
    mkdir -p "$RUN_DIR"/{etc,munge,munge-socket,state,spool,pid,log}
    # munged wants its key directory private and the socket's directories searchable by
    # all (clients of any user connect), none of them writable by others.
    chmod 755 "$RUN_DIR" "$RUN_DIR/munge-socket"
    chmod 700 "$RUN_DIR/munge"
    local key="$RUN_DIR/munge/munge.key" log="$RUN_DIR/log"
    if [[ ! -s "$key" ]]; then
        mungekey --create --keyfile="$key" || die "mungekey could not create $key"
    fi
    write_config
    write_srun_wrapper

    # Each daemon forks into the background and writes its PID file, which stop reads.
    munged --key-file="$key" --socket="$MUNGE_SOCKET" --pid-file="$RUN_DIR/pid/munged.pid" \
        --log-file="$log/munged.log" --seed-file="$RUN_DIR/munge/munged.seed" \
        2>>"$log/munged.log" || die "munged failed to start: read $log/munged.log"
    wait_for 10 "$log/munged.log" test -S "$MUNGE_SOCKET"
    wait_for 10 "$log/munged.log" pid_of munged
    # -c: do not recover jobs and node states of an earlier run from the state directory.
    slurmctld -c -f "$SLURM_CONF" 2>>"$log/slurmctld.log" ||
        die "slurmctld failed to start: read $log/slurmctld.log"
    wait_for 10 "$log/slurmctld.log" pid_of slurmctld
    # -N localhost: this node's name in slurm.conf, whatever the machine's hostname.
    slurmd -f "$SLURM_CONF" -N localhost 2>>"$log/slurmd.log" ||
        die "slurmd failed to start: read $log/slurmd.log"
    wait_for 10 "$log/slurmd.log" pid_of slurmd
    wait_for "$START_TIMEOUT_S" "$log/slurmctld.log and $log/slurmd.log" node_idle
    echo "SLURM running on localhost; clients need: $(client_env)"
}

cmd_stop() {
    local name pid waited
    # Jobs first: their slurmstepd processes would outlive slurmd.
    if pid_of slurmctld >/dev/null && pid_of munged >/dev/null; then
        timeout 10 scancel --full --user="$(id -un)" 2>/dev/null || true
        waited=0
        while [[ -n "$(timeout 10 squeue --noheader --states=RUNNING,COMPLETING 2>/dev/null)" ]] &&
            ((waited < 30)); do
            sleep 1
            waited=$((waited + 1))
        done
    fi
    for name in "${DAEMONS[@]}"; do
        pid="$(pid_of "$name")" || continue
        kill -TERM "$pid" 2>/dev/null || true
        waited=0
        while kill -0 "$pid" 2>/dev/null && ((waited < 60)); do
            sleep 0.5
            waited=$((waited + 1))
        done
        if kill -0 "$pid" 2>/dev/null; then
            echo "localhost_slurm.sh: $name ($pid) ignored SIGTERM for 30 s; killing it" >&2
            kill -KILL "$pid" 2>/dev/null || true
        fi
        rm -f "$RUN_DIR/pid/$name.pid"
        echo "stopped $name ($pid)"
    done
}

cmd_status() {
    local name pid state=0
    for name in "${DAEMONS[@]}"; do
        if pid="$(pid_of "$name")"; then
            echo "$name: running ($pid)"
        else
            echo "$name: not running"
            state=3
        fi
    done
    if ((state == 0)); then
        echo "node localhost: $(node_state)"
        echo "clients need: $(client_env)"
    fi
    return "$state"
}

cmd_check() {
    local out
    all_running || die "SLURM is not running: run tools/slurm/localhost_slurm.sh start"
    out="$(mktemp)"
    # --wait: sbatch returns when the job ends, with the job's exit status.
    timeout 120 sbatch --wait --parsable --output="$out" --wrap hostname >/dev/null ||
        die "sbatch --wrap hostname did not complete: read $RUN_DIR/log/slurmd.log"
    echo "job ran on $(<"$out")"
    rm -f "$out"
}

case "${1:-}" in
    install) cmd_install ;;
    start) cmd_start ;;
    stop) cmd_stop ;;
    status) cmd_status ;;
    check) cmd_check ;;
    env) client_env ;;
    *) die "usage: $0 install|start|stop|status|check|env" ;;
esac
