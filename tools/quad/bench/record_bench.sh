#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Recorder throughput, side by side in one run: a subscriber that discards what it receives,
# then quad record uncompressed and with zstd, each taking COUNT reliable map updates of SIZE
# bytes from a publisher that sends as fast as flow control lets it. With -n RUNS the three
# sides take turns RUNS times and the medians are compared: single runs of the reliable
# protocol over loopback scatter by 1.5x or more.
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

row() {  # size count side seconds messages loss
  awk -v size="$1" -v count="$2" -v side="$3" -v s="$4" -v n="$5" -v loss="$6" 'BEGIN {
    printf "%-8s %-7s %-11s %9.3f %10.0f %9.1f  %s\n", size, count, side, s, n / s, n * size / s / 1e6, loss }'
  awk -v side="$3" -v s="$4" -v n="$5" 'BEGIN { print side, n / s }' >> "$tmp/rates"
}

printf "%-8s %-7s %-11s %9s %10s %9s  %s\n" SIZE COUNT SIDE SECONDS MSG/S MB/S LOSS
for spec in "${specs[@]}"; do
  size=${spec%%:*}
  count=${spec##*:}
  : > "$tmp/rates"
  for _ in $(seq "$runs"); do
    export QUAD_DOMAIN_ID=$((RANDOM % 100 + 120))
    # The discarding subscriber.
    "$bench" discard "$count" 120 > "$tmp/discard.out" &
    discard=$!
    sleep 1
    "$bench" publish "$size" "$count" > /dev/null
    wait "$discard" || true
    # Its result line (the middleware's warnings may come before it on the same stream).
    read -r _ n _ s _ < <(grep '^received' "$tmp/discard.out")
    row "$size" "$count" discard "$s" "$n" "$n of $count received"
    # quad record, uncompressed and zstd. The publisher returns once every sample is
    # acknowledged, so the recorder, stopped then, has them all.
    for compression in none zstd; do
      "$quad" record -q -o "$tmp/bench.mcap" --compression "$compression" quad/mapping/update > /dev/null 2>&1 &
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
        "$(sed 's/.*received/received/' <<< "$line")"
    done
  done
  if [ "$runs" -gt 1 ]; then
    # Medians of msg/s per side, and each against the discarding subscriber's.
    for side in discard record/none record/zstd; do
      awk -v side="$side" '$1 == side { print $2 }' "$tmp/rates" | sort -g |
        awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }' > "$tmp/median.$(basename "$side")"
    done
    base=$(cat "$tmp/median.discard")
    for side in discard record/none record/zstd; do
      awk -v size="$size" -v count="$count" -v side="$side" -v m="$(cat "$tmp/median.$(basename "$side")")" -v base="$base" -v runs="$runs" 'BEGIN {
        printf "%-8s %-7s %-11s median of %d: %.0f msg/s, %.1f MB/s, %.2fx the discarding subscriber\n", size, count, side, runs, m, m * size / 1e6, m / base }'
    done
  fi
done
