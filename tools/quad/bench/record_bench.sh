#!/usr/bin/env bash
# Recorder throughput, side by side in one run: a subscriber that discards what it receives,
# then quad record, each taking COUNT reliable map updates of SIZE bytes from a publisher
# that sends as fast as flow control lets it.
#   tools/quad/bench/record_bench.sh BUILD_DIR [SIZE:COUNT ...]   (default: 100:200000 1048576:200)
set -euo pipefail
build=${1:?usage: record_bench.sh BUILD_DIR [SIZE:COUNT ...]}
shift
specs=("$@")
if [ ${#specs[@]} -eq 0 ]; then
  specs=(100:200000 1048576:200)
fi
quad="$build/tools/quad/quad"
bench="$build/tools/quad/quad_record_bench"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export QUAD_TRANSPORT=udp

printf "%-8s %-7s %-10s %12s %12s %10s  %s\n" SIZE COUNT SIDE SECONDS MSG/S MB/S LOSS
for spec in "${specs[@]}"; do
  size=${spec%%:*}
  count=${spec##*:}
  export QUAD_DOMAIN_ID=$((RANDOM % 100 + 120))
  # The discarding subscriber.
  "$bench" discard "$count" 120 > "$tmp/discard.out" &
  discard=$!
  sleep 1
  "$bench" publish "$size" "$count" > /dev/null
  wait "$discard" || true
  read -r _ n _ s _ < "$tmp/discard.out"
  awk -v size="$size" -v count="$count" -v n="$n" -v s="$s" 'BEGIN {
    printf "%-8s %-7s %-10s %12.3f %12.0f %10.1f  %d of %d received\n", size, count, "discard", s, n / s, n * size / s / 1e6, n, count }'
  # quad record, uncompressed and zstd.
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
    loss=$(sed 's/.*received/received/' <<< "$line")
    awk -v size="$size" -v count="$count" -v n="$n" -v rate="$rate" -v side="record/$compression" -v loss="$loss" 'BEGIN {
      s = (n - 1) / rate; printf "%-8s %-7s %-10s %12.3f %12.0f %10.1f  %s\n", size, count, side, s, n / s, n * size / s / 1e6, loss }'
  done
done
