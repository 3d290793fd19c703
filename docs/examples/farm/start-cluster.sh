#!/bin/sh
# start-cluster.sh DIR: a one-node Slurm cluster on this machine, for trying submit.sh. Needs
# Debian's slurm-wlm and munge packages (apt-get install slurm-wlm munge) and root. Writes
# slurm.conf under DIR, starts munged, slurmctld and slurmd, and waits until the node is idle.
# Stop it with: kill $(cat DIR/*.pid)
set -eu
dir=$(mkdir -p "$1" && cd "$1" && pwd)
host=$(hostname -s)
cpus=$(nproc)
mkdir -p "$dir/spool/ctld" "$dir/spool/d" /run/munge
[ -f /etc/munge/munge.key ] || mungekey --create 2>/dev/null || create-munge-key
chown -R munge:munge /etc/munge /run/munge 2>/dev/null || true
# --force: as root, munged refuses to start over a log directory it finds insecure.
munged --force --pid-file="$dir/munged.pid" 2>/dev/null || true
cat >"$dir/slurm.conf" <<CONF
ClusterName=rt-test
SlurmctldHost=$host
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SlurmUser=root
StateSaveLocation=$dir/spool/ctld
SlurmdSpoolDir=$dir/spool/d
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ReturnToService=2
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -c
slurmd -c
for _ in $(seq 30); do
    sinfo -h -o %t 2>/dev/null | grep -q idle && { echo "export SLURM_CONF=$SLURM_CONF"; exit 0; }
    sleep 1
done
echo "start-cluster.sh: the node did not come up; see $dir/*.log" >&2
exit 1
