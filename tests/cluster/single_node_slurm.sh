#!/usr/bin/env bash
# Run the SLURM tests of `hollowbody calibrate --cluster slurm` against a real
# single-node SLURM started here from the distribution's packages (Debian or
# Ubuntu, as root, e.g. in a CI container):
#
#   tests/cluster/single_node_slurm.sh
#
# Installs slurmctld, slurmd, slurm-client and munge (apt-get), writes a
# one-node configuration (this host, its cores, partition "debug") into
# /etc/slurm/slurm.conf with its state in a temporary folder, starts munged,
# slurmctld and slurmd, runs tests/unit/calibrate/test_cluster.py, and stops
# the daemons it started.
set -euo pipefail

if [ "$(id -u)" != 0 ]; then
    echo "single_node_slurm.sh: needs root (installs and starts the SLURM daemons)" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
host=$(hostname)
cores=$(nproc)
mem=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2 ))

DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurmctld slurmd slurm-client munge

mkdir -p "$work/state" "$work/spool" /run/munge
cat > /etc/slurm/slurm.conf <<CONF
ClusterName=single
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$cores RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

chown -R munge:munge /etc/munge /run/munge
su -s /bin/sh munge -c /usr/sbin/munged
/usr/sbin/slurmctld
/usr/sbin/slurmd

stop() {
    for f in "$work/slurmd.pid" "$work/slurmctld.pid" /run/munge/munged.pid; do
        [ -f "$f" ] && kill "$(cat "$f")" 2>/dev/null || true
    done
}
trap stop EXIT

for _ in $(seq 30); do
    sinfo -h -o %T 2>/dev/null | grep -q idle && break
    sleep 1
done
sinfo
cd "$here"
PYTHONPATH="$here/src${PYTHONPATH:+:$PYTHONPATH}" python3 -m pytest -q -rs tests/unit/calibrate/test_cluster.py
