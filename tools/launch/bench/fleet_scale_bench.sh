#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A fleet's cost as it grows, simple discovery against a discovery server, side by side for
# each size: N vehicles (each with its mapper, planner, estimator and controller; one plant for
# all) fly parallel lanes across configs/worlds/open.yaml in lockstep for SIM_S seconds of sim
# time, once with multicast (simple) discovery and once with `fastdds discovery` started by the
# launcher, the two taking turns; the modules and the mission are bringup/fleet.yaml's. For
# each run, from its summary.json and the host's packet counters:
#   startup_s     launcher start to the first vehicle state: every module started (each after
#                 the writers it needs were discovered) and the plant's lockstep barrier met
#   rtf           sim time over the flight's wall time (first vehicle state to the last)
#   cpu/veh       CPU time of every process of the run (modules, plant, discovery server,
#                 launcher) per vehicle per second of sim time [core-seconds per sim second]
#   rss/part      the modules' peak resident memory, mean and largest [MiB]; each module is
#                 one DDS participant
#   meta_MB       UDP bytes sent to the domain's discovery ports (participant and endpoint
#                 discovery, and what rides with them) and to the discovery server
#   user_MB       UDP bytes sent to the domain's user-traffic ports (the topics' samples)
# The bytes are counted by iptables on the OUTPUT chain (every datagram a process of this host
# sends, loopback and multicast included), so the script runs as root, on an otherwise quiet
# machine: anything else on the domain's ports would be counted too.
# A run that does not reach SIM_S (a stalled lockstep ends at its wall timeout, 60 s + 6 s per
# vehicle per second of sim time) says why in its last column, and its rtf is what it flew.
# -l LEASE gives every participant of the runs that lease [s] (the manifest's discovery.lease)
# instead of the QoS profile's 2 s: on two cores eight vehicles need a longer one (docs/fleet.md).
#   tools/launch/bench/fleet_scale_bench.sh BUILD_DIR [-n RUNS] [-t SIM_S] [-d DOMAIN] [-l LEASE] [N ...]
#   (default: 1 run, 20 s, domain 170, the profile's lease, N = 1 2 4 8 16)
set -euo pipefail
build=${1:?usage: fleet_scale_bench.sh BUILD_DIR [-n RUNS] [-t SIM_S] [-d DOMAIN] [-l LEASE] [N ...]}
shift
runs=1
sim_s=20
domain=170
lease=
while [[ ${1:-} == -* ]]; do
  case "$1" in
    -n) runs=${2:?-n needs a number of runs} ;;
    -t) sim_s=${2:?-t needs seconds of sim time} ;;
    -d) domain=${2:?-d needs a domain id} ;;
    -l) lease=${2:?-l needs seconds} ;;
    *)
      echo "fleet_scale_bench.sh: unknown option $1" >&2
      exit 2
      ;;
  esac
  shift 2
done
sizes=("$@")
if [ ${#sizes[@]} -eq 0 ]; then
  sizes=(1 2 4 8 16)
fi
for n in "${sizes[@]}"; do
  if ! [[ $n =~ ^[0-9]+$ ]] || ((n < 1 || n > 16)); then
    echo "fleet_scale_bench.sh: $n vehicles: the lanes of the open world hold 1 to 16" >&2
    exit 2
  fi
done
if [[ $(id -u) -ne 0 ]]; then
  echo "fleet_scale_bench.sh: counting the traffic takes iptables: run as root" >&2
  exit 1
fi
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
quad=$(cd "$build" && pwd)/tools/quad/quad
server_port=11811
base=$((7400 + 250 * domain))
if ((base + 249 > 65535)); then
  echo "fleet_scale_bench.sh: domain $domain: its ports pass 65535" >&2
  exit 2
fi
tmp=$(mktemp -d)
chain=QUAD_FLEET_SCALE

cleanup() {
  iptables -D OUTPUT -j "$chain" 2> /dev/null || true
  iptables -F "$chain" 2> /dev/null || true
  iptables -X "$chain" 2> /dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# One counting rule for each port of the domain and for the server's; none drops anything.
iptables -N "$chain"
iptables -I OUTPUT -j "$chain"
for ((p = base; p < base + 250; ++p)); do
  iptables -A "$chain" -p udp --dport "$p"
done
iptables -A "$chain" -p udp --dport "$server_port"

# The RTPS port mapping (d0 = 0, d1 = 10, d2 = 1, d3 = 11, participant gain 2): discovery on
# the base port (multicast) and base + 10 + 2i (participant i's unicast), user traffic on
# base + 1 and base + 11 + 2i; the discovery server's port carries discovery only.
bytes() {  # prints "meta user" bytes counted since the last zeroing
  iptables -L "$chain" -v -x -n | awk -v base="$base" -v server="$server_port" '
    $0 ~ /dpt:/ {
      match($0, /dpt:[0-9]+/)
      port = substr($0, RSTART + 4, RLENGTH - 4) + 0
      off = port - base
      if (port == server || off == 0 || (off >= 10 && off % 2 == 0)) meta += $2; else user += $2
    }
    END { printf "%d %d\n", meta, user }'
}

manifest() {  # N discovery: writes the manifest and prints its path
  local n=$1 kind=$2 file="$tmp/fleet_${1}_${2}.yaml"
  {
    echo "name: fleet-scale"
    echo "world: $root/configs/worlds/open.yaml"
    echo "mode: lockstep"
    echo "state: estimate"
    echo "transport: udp"
    echo "domain: $domain"
    local lease_key=${lease:+, lease: $lease}
    if [ "$kind" = server ]; then
      echo "discovery: {kind: server, port: $server_port$lease_key}"
    elif [ -n "$lease" ]; then
      echo "discovery: {lease: $lease}"
    fi
    echo "vehicles:"
    # Lanes 2.5 m apart, centred on y = 0, from x = 0 to x = 40.
    for ((k = 0; k < n; ++k)); do
      local y
      y=$(awk -v k="$k" -v n="$n" 'BEGIN { printf "%.2f", (k - (n - 1) / 2) * 2.5 }')
      echo "  - {id: $((k + 1)), start: [0, $y, 0], goal: [40, $y, 2]}"
    done
    # The modules and the mission as the shipped fleet flies them, with absolute paths and
    # this run's length of sim time.
    sed -n '/^modules:/,$p' "$root/bringup/fleet.yaml" |
      sed "s#\.\./configs#$root/configs#g; s/sim\.duration: .*/sim.duration: $sim_s/"
  } > "$file"
  echo "$file"
}

run() {  # N discovery rep
  local n=$1 kind=$2 file log="$tmp/run_${1}_${2}_${3}"
  file=$(manifest "$n" "$kind")
  iptables -Z "$chain"
  "$quad" launch "$file" --quiet --no-record --seed 1 --log-dir "$log" --summary "$log.json" \
    --wall-timeout "$(awk -v n="$n" -v t="$sim_s" 'BEGIN { printf "%d", 60 + 6 * n * t }')" > "$log.out" 2>&1 || true
  if [ ! -s "$log.json" ]; then
    echo "fleet_scale_bench.sh: $n vehicles, $kind discovery: no summary; the launcher said:" >&2
    tail -20 "$log.out" >&2
    exit 1
  fi
  read -r meta user < <(bytes)
  python3 - "$log.json" "$n" "$kind" "$meta" "$user" "$sim_s" << 'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
n, kind, meta, user = int(sys.argv[2]), sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
procs = s["processes"]
cpu = sum(p["cpu_seconds"] or 0.0 for p in procs.values())
modules = [p["max_rss_mib"] for name, p in procs.items()
           if name not in ("launch", "discovery", "record") and p["max_rss_mib"] is not None]
sim, flight, startup = s["sim_seconds"], s["flight_wall_seconds"] or 0.0, s["startup_seconds"]
startup = float("nan") if startup is None else startup
print(f"{n:>3} {kind:<7} {startup:9.1f} {sim / flight if flight else 0.0:6.2f} {cpu / n / sim if sim else 0.0:8.3f} "
      f"{sum(modules) / len(modules):8.1f} {max(modules):8.1f} {meta / 1e6:9.2f} {user / 1e6:9.1f} "
      f"{len(modules):6d} {sim:6.1f} {flight:7.1f}  {'ran' if sim >= float(sys.argv[6]) - 0.01 else 'stopped: ' + (s['failure'] or s['outcome'])[:60]}")
EOF
}

echo "# $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), lockstep, ${sim_s} s of sim time a run"
printf "%3s %-7s %9s %6s %8s %8s %8s %9s %9s %6s %6s %7s  %s\n" N disc startup_s rtf cpu/veh rss_mean rss_max meta_MB user_MB procs sim_s wall_s end
for n in "${sizes[@]}"; do
  for ((rep = 1; rep <= runs; ++rep)); do
    # Alternate which goes first, so that neither always runs on a fresher machine.
    if ((rep % 2)); then order=(simple server); else order=(server simple); fi
    for kind in "${order[@]}"; do
      run "$n" "$kind" "$rep"
    done
  done
done
