#!/usr/bin/env bash
# slurm_cluster.sh start|stop DIR: a throwaway single-node Slurm cluster for tests and benchmarks (issue 18):
# munged (its own key and socket, folders owned by the munge user), slurmctld and slurmd (non-default ports,
# state, spool and logs under DIR), all started in the foreground as background processes of this machine, so no
# systemd is needed (CI: root on a fresh Debian 12). `start` waits (bounded) until the node is idle and writes
# DIR/env (SLURM_CONF for the client commands); `stop` ends exactly the processes it started (DIR/*.pid).
# Needs root (slurmd runs jobs as their submitter, munged runs as munge) and Debian's slurm-wlm and munge.
set -u
action="$1"
dir="$2"

stop() {
  for name in slurmd slurmctld munged; do
    [ -f "$dir/$name.pid" ] || continue
    pid=$(cat "$dir/$name.pid")
    kill "$pid" 2>/dev/null
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null
    rm -f "$dir/$name.pid"
  done
}

if [ "$action" = stop ]; then
  stop
  exit 0
fi
[ "$action" = start ] || { echo "usage: slurm_cluster.sh start|stop DIR" >&2; exit 2; }
[ "$(id -u)" = 0 ] || { echo "slurm_cluster.sh: needs root (slurmd, munged as munge)" >&2; exit 1; }
for p in munged slurmctld slurmd sbatch sinfo; do
  command -v "$p" >/dev/null || { echo "slurm_cluster.sh: $p missing (apt-get install slurm-wlm munge)" >&2; exit 1; }
done

mkdir -p "$dir"/{munge,socket,state,spool,log}
dir=$(cd "$dir" && pwd)
chmod 711 "$dir" "$(dirname "$dir")"  # munged runs as munge: it must traverse to its folder (mktemp -d is 700)
chown munge:munge "$dir/munge" "$dir/socket"
chmod 700 "$dir/munge"   # key, seed, log: the munge user's only
chmod 755 "$dir/socket"  # munged requires its socket's folder to be reachable by every client
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chown munge:munge "$dir/munge/munge.key"
chmod 400 "$dir/munge/munge.key"
socket="$dir/socket/munge.socket"
setpriv --reuid munge --regid munge --init-groups munged --foreground --key-file="$dir/munge/munge.key" \
  --socket="$socket" --log-file="$dir/munge/munged.log" --pid-file="$dir/munge/munged.pidfile" \
  --seed-file="$dir/munge/munged.seed" >"$dir/log/munged.out" 2>&1 &
echo $! >"$dir/munged.pid"
for _ in $(seq 100); do [ -S "$socket" ] && break; sleep 0.1; done
[ -S "$socket" ] || { echo "munged did not start: $(cat "$dir/log/munged.out" "$dir/munge/munged.log" 2>/dev/null)" >&2; stop; exit 1; }

# Ports: derived from this shell's PID so that parallel clusters (ctest -j) do not collide; never the defaults.
port=$((20000 + ($$ % 2000) * 2))
host=$(hostname -s)
cat >"$dir/slurm.conf" <<EOF
ClusterName=idkfarm
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/state/slurmctld.pidfile
SlurmdPidFile=$dir/spool/slurmd.pidfile
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
MinJobAge=10
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=farm Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
echo "export SLURM_CONF=$dir/slurm.conf" >"$dir/env"
export SLURM_CONF="$dir/slurm.conf"
slurmctld -D -i >"$dir/log/slurmctld.out" 2>&1 &
echo $! >"$dir/slurmctld.pid"
slurmd -D -N "$host" >"$dir/log/slurmd.out" 2>&1 &
echo $! >"$dir/slurmd.pid"
for _ in $(seq 150); do
  state=$(sinfo -h -N -o %T 2>/dev/null)
  [ "$state" = idle ] && exit 0
  sleep 0.2
done
echo "slurm_cluster.sh: the node is not idle after 30 s (state '${state:-}'):" >&2
tail -5 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" "$dir/log/slurmctld.out" "$dir/log/slurmd.out" >&2 2>/dev/null
stop
exit 1
