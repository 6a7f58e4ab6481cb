#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Recorder cost, side by side in one run: a subscriber that discards what it receives, then
# quad record uncompressed and with zstd, each taking the same COUNT reliable map updates of
# SIZE bytes from a publisher that sends as fast as flow control lets it. Each side's
# process is charged the CPU time it took (user + system, its rusage), less what the same
# side takes started and stopped with no traffic (joining the domain, discovery, the wait:
# measured first), per message received; the receiving rate is shown as well, but it measures
# how the reliable protocol paces itself more than the receiver's work. With -n RUNS the
# three sides take turns RUNS times and the medians are compared.
#   tools/quad/bench/record_bench.sh BUILD_DIR [-n RUNS] [SIZE:COUNT ...]   (default: 100:200000 1048576:200)
set -euo pipefail
build=${1:?usage: record_bench.sh BUILD_DIR [-n RUNS] [SIZE:COUNT ...]}
shift
runs=1
if [ "${1:-}" = "-n" ]; then
  runs=${2:?-n needs a number of runs}
  shift 2
fi
specs=("$@")
if [ ${#specs[@]} -eq 0 ]; then
  specs=(100:200000 1048576:200)
fi
quad="$build/tools/quad/quad"
bench="$build/tools/quad/quad_record_bench"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export QUAD_TRANSPORT=udp

row() {  # size count side seconds messages cpu_file loss
  local idle
  idle=$(cat "$tmp/idle.${3%%/*}")
  local cpu
  cpu=$(cat "$6")
  awk -v size="$1" -v count="$2" -v side="$3" -v s="$4" -v n="$5" -v c="$cpu" -v i="$idle" -v loss="$7" 'BEGIN {
    printf "%-8s %-7s %-11s %8.3f %11.2f %9.3f %10.0f  %s\n", size, count, side, c, 1e6 * (c - i) / n, s, n / s, loss }'
  awk -v side="$3" -v n="$5" -v c="$cpu" -v i="$idle" -v s="$4" 'BEGIN { print side, 1e6 * (c - i) / n, n / s }' >> "$tmp/results"
}

median() {  # side column: the median of that column of the side's rows
  awk -v side="$1" -v col="$2" '$1 == side { print $col }' "$tmp/results" | sort -g |
    awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'
}

# Each side with no traffic: started, left for the time the runs below wait, stopped.
export QUAD_DOMAIN_ID=$((RANDOM % 100 + 120))
"$bench" cpu "$tmp/cpu" -- "$bench" discard 1 1 > /dev/null 2>&1 || true
cp "$tmp/cpu" "$tmp/idle.discard"
"$bench" cpu "$tmp/cpu" -- "$quad" record -q -o "$tmp/idle.mcap" quad/mapping/update > /dev/null 2>&1 &
recorder=$!
sleep 1
kill -INT "$recorder"
wait "$recorder" || true
cp "$tmp/cpu" "$tmp/idle.record"
echo "with no traffic: discarding subscriber $(cat "$tmp/idle.discard") s of CPU, quad record $(cat "$tmp/idle.record") s"

printf "%-8s %-7s %-11s %8s %11s %9s %10s  %s\n" SIZE COUNT SIDE CPU_S CPU_US/MSG SECONDS MSG/S LOSS
for spec in "${specs[@]}"; do
  size=${spec%%:*}
  count=${spec##*:}
  : > "$tmp/results"
  for _ in $(seq "$runs"); do
    export QUAD_DOMAIN_ID=$((RANDOM % 100 + 120))
    # The discarding subscriber.
    "$bench" cpu "$tmp/cpu" -- "$bench" discard "$count" 120 > "$tmp/discard.out" &
    discard=$!
    sleep 1
    "$bench" publish "$size" "$count" > /dev/null
    wait "$discard" || true
    # Its result line (the middleware's warnings may come before it on the same stream).
    read -r _ n _ s _ < <(grep '^received' "$tmp/discard.out")
    row "$size" "$count" discard "$s" "$n" "$tmp/cpu" "$n of $count received"
    # quad record, uncompressed and zstd. The publisher returns once every sample is
    # acknowledged, so the recorder, stopped then, has them all.
    for compression in none zstd; do
      "$bench" cpu "$tmp/cpu" -- "$quad" record -q -o "$tmp/bench.mcap" --compression "$compression" quad/mapping/update \
        > /dev/null 2>&1 &
      recorder=$!
      sleep 1
      "$bench" publish "$size" "$count" > /dev/null
      kill -INT "$recorder"
      wait "$recorder" || true
      "$quad" bag info "$tmp/bench.mcap" > "$tmp/info.out" || true
      line=$(grep "quad/mapping/update" "$tmp/info.out")
      n=$(awk '{print $3}' <<< "$line")
      rate=$(awk '{print $4}' <<< "$line")
      row "$size" "$count" "record/$compression" "$(awk -v n="$n" -v r="$rate" 'BEGIN { print (n - 1) / r }')" "$n" \
        "$tmp/cpu" "$(sed 's/.*received/received/' <<< "$line")"
    done
  done
  if [ "$runs" -gt 1 ]; then
    # Medians per side of the CPU per message and of the rate, each against the discarding
    # subscriber's.
    base_cpu=$(median discard 2)
    base_rate=$(median discard 3)
    for side in discard record/none record/zstd; do
      awk -v size="$size" -v count="$count" -v side="$side" -v c="$(median "$side" 2)" -v r="$(median "$side" 3)" \
        -v bc="$base_cpu" -v br="$base_rate" -v runs="$runs" 'BEGIN {
        printf "%-8s %-7s %-11s median of %d: %.2f us CPU/msg (%.2fx the discarding subscriber), %.0f msg/s (%.2fx)\n",
          size, count, side, runs, c, c / bc, r, r / br }'
    done
  fi
done
