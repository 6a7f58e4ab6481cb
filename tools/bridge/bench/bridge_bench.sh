#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# quad bridge's cost, side by side in one run: vehicle states published at RATE Hz for
# SECONDS on quad/sim/state reach, at once, a plain DDS subscriber (quad_bridge_bench listen)
# and a Foxglove WebSocket client through quad bridge (tests/foxglove/bridge_latency.mjs).
# Each side prints its latency (receive time minus the Header's publish time, on this
# machine's one clock): count, median, 99th percentile and maximum; the bridge's process and
# the plain subscriber's are charged their CPU time (rusage: user + system) over the same
# run, and the difference is what the bridge adds. -n RUNS repeats the run.
#   tools/bridge/bench/bridge_bench.sh BUILD_DIR [-n RUNS] [RATE] [SECONDS]   (default 250 Hz, 20 s)
set -euo pipefail
build=${1:?usage: bridge_bench.sh BUILD_DIR [-n RUNS] [RATE] [SECONDS]}
shift
runs=1
if [ "${1:-}" = "-n" ]; then
  runs=${2:?-n needs a number of runs}
  shift 2
fi
rate=${1:-250}
seconds=${2:-20}
source_dir=$(cd "$(dirname "$0")/../../.." && pwd)
quad="$build/tools/quad/quad"
bench="$build/tools/bridge/quad_bridge_bench"
cpu="$build/tools/quad/quad_record_bench"
node_dir="$build/foxglove"
if [ ! -d "$node_dir/node_modules/@foxglove/ws-protocol" ]; then
  mkdir -p "$node_dir"
  cp "$source_dir/tests/foxglove/package.json" "$source_dir/tests/foxglove/package-lock.json" "$node_dir/"
  npm ci --no-audit --no-fund --prefix "$node_dir" > /dev/null
fi
cp "$source_dir/tests/foxglove/bridge_latency.mjs" "$node_dir/"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export QUAD_TRANSPORT=udp
export QUAD_DOMAIN_ID=$((RANDOM % 60 + 160))
port=$((20000 + RANDOM % 20000))
listen_s=$((seconds + 5))

printf "%-4s %-22s %8s %10s %10s %10s %8s\n" run side samples median_us p99_us max_us cpu_s
for run in $(seq 1 "$runs"); do
  "$cpu" cpu "$tmp/bridge.cpu" -- "$quad" bridge -q --port "$port" > "$tmp/bridge.out" 2>&1 &
  bridge=$!
  for _ in $(seq 1 100); do
    grep -q "listening" "$tmp/bridge.out" && break
    sleep 0.1
  done
  "$cpu" cpu "$tmp/listen.cpu" -- "$bench" listen "$listen_s" > "$tmp/listen.out" &
  listener=$!
  node "$node_dir/bridge_latency.mjs" "ws://127.0.0.1:$port" "$listen_s" > "$tmp/ws.out" &
  client=$!
  sleep 1
  "$bench" publish "$rate" "$seconds" > /dev/null
  wait "$listener" "$client"
  kill -INT "$bridge"
  wait "$bridge" || true
  for side in listen ws; do
    read -r _ n _ median _ p99 _ max < "$tmp/$side.out"
    if [ "$side" = listen ]; then
      name="plain DDS subscriber"
      c=$(cat "$tmp/listen.cpu")
    else
      name="bridge + WebSocket"
      c=$(cat "$tmp/bridge.cpu")
    fi
    printf "%-4s %-22s %8s %10s %10s %10s %8.3f\n" "$run" "$name" "$n" "$median" "$p99" "$max" "$c"
  done
done
