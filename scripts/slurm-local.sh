#!/usr/bin/env bash
# A one-node Slurm in a folder, for trying `kestrel mc --slurm` and for its
# test (docs/monte-carlo.md).  Needs root, slurm-wlm and munge
# (scripts/install-deps.sh host).
#   scripts/slurm-local.sh start DIR   munged (if not running), slurmctld and slurmd;
#                                      then: export SLURM_CONF=DIR/slurm.conf
#   scripts/slurm-local.sh stop DIR    stops the two Slurm daemons started in DIR
# Everything (state, spool, logs, pid files) stays in DIR; ports 16817/16818.
# No cgroups (slurm 22.05 cannot disable the cgroup plugin in a cgroup.conf).
set -euo pipefail
cmd="${1:-}"; W="${2:-}"
[ -n "$cmd" ] && [ -n "$W" ] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
mkdir -p "$W"
W=$(cd "$W" && pwd)

stop() {
  for p in "$W/run/slurmd.pid" "$W/run/slurmctld.pid"; do
    [ -f "$p" ] && kill "$(cat "$p")" 2>/dev/null || true
  done
}

if [ "$cmd" = stop ]; then stop; exit 0; fi
[ "$cmd" = start ] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ "$(id -u)" -eq 0 ] || { echo "slurm-local: needs root (SlurmUser=root)" >&2; exit 1; }
PATH="$PATH:/usr/sbin"
for t in munged slurmctld slurmd sinfo; do
  command -v $t > /dev/null || { echo "slurm-local: $t not installed (scripts/install-deps.sh host)" >&2; exit 1; }
done

# munge: a key and the daemon (once per machine)
if ! munge -n 2>/dev/null | unmunge > /dev/null 2>&1; then
  mkdir -p /etc/munge /var/lib/munge /var/log/munge /run/munge
  [ -f /etc/munge/munge.key ] || dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key 2>/dev/null
  chown -R munge:munge /etc/munge /var/lib/munge /var/log/munge /run/munge
  chmod 400 /etc/munge/munge.key
  su -s /bin/sh munge -c /usr/sbin/munged
  for _ in $(seq 1 50); do munge -n 2>/dev/null | unmunge > /dev/null 2>&1 && break; sleep 0.1; done
  munge -n | unmunge > /dev/null || { echo "slurm-local: munge does not work" >&2; exit 1; }
fi

H=$(hostname -s); C=$(nproc)
mkdir -p "$W/state" "$W/spool" "$W/run" "$W/log"
cat > "$W/slurm.conf" <<EOF
ClusterName=kestrel-local
SlurmctldHost=$H
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$W/state
SlurmdSpoolDir=$W/spool
SlurmctldPidFile=$W/run/slurmctld.pid
SlurmdPidFile=$W/run/slurmd.pid
SlurmctldLogFile=$W/log/slurmctld.log
SlurmdLogFile=$W/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SlurmctldPort=16817
SlurmdPort=16818
NodeName=$H CPUs=$C State=UNKNOWN
PartitionName=debug Nodes=$H Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$W/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 1 100); do
  if sinfo -h -o "%T" 2>/dev/null | grep -qE "idle|mixed|allocated"; then
    echo "slurm-local: node $H up ($C CPUs); export SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.2
done
echo "slurm-local: the node did not come up in 20 s; logs:" >&2
tail -5 "$W/log/slurmctld.log" "$W/log/slurmd.log" >&2 || true
stop
exit 1
