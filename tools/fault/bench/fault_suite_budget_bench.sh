#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The fault suite (tests/scenarios/*.yaml, as `ctest -L fault` runs it) with the map update's and
# the path's budgets as they ship against the round-synchronous lockstep they replaced
# (QUAD_MAP_BUDGET_MS=0 QUAD_PATH_BUDGET_MS=0: the clock waits every round for the planner, and
# at every depth frame until its update is out), side by side: each scenario runs once each way,
# the order turned at every scenario so that neither side always goes first. For each run:
#   scenario, side, its exit status (0: every expectation met) and its wall time,
# then each side's total wall time, passes, and the ratio of the totals. Scenarios whose
# manifest flies in real time run the same both ways and count on both sides.
#   tools/fault/bench/fault_suite_budget_bench.sh BUILD_DIR [-d DOMAIN] [SCENARIO...]
#   (default: every scenario of tests/scenarios, domain 123)
set -euo pipefail
build=${1:?usage: fault_suite_budget_bench.sh BUILD_DIR [-d DOMAIN] [SCENARIO...]}
shift
domain=123
if [[ ${1:-} == -d ]]; then
  domain=${2:?-d needs a domain id}
  shift 2
fi
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
quad="$build/tools/quad/quad"
[[ -x $quad ]] || { echo "fault_suite_budget_bench.sh: no $quad: build first" >&2; exit 1; }
scenarios=("$@")
((${#scenarios[@]})) || scenarios=("$root"/tests/scenarios/*.yaml)
out=$(mktemp -d /tmp/quad_fault_budget_XXXXXX)
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "runs in $out"
runOne() {  # scenario side map_ms path_ms
  local name dir start rc=0
  name=$(basename "$1" .yaml)
  dir="$out/$name.$2"
  start=$(date +%s.%N)
  QUAD_MAP_BUDGET_MS=$3 QUAD_PATH_BUDGET_MS=$4 "$quad" fault "$1" --domain "$domain" -q --no-report \
    --wall-timeout 280 --log-dir "$dir" > "$dir.out" 2>&1 || rc=$?
  echo "$name $2 $rc $(echo "$(date +%s.%N) - $start" | bc)" | tee -a "$out/runs.txt"
}
turn=0
for s in "${scenarios[@]}"; do
  if ((turn % 2 == 0)); then
    runOne "$s" synchronous 0 0
    runOne "$s" budgets "" ""
  else
    runOne "$s" budgets "" ""
    runOne "$s" synchronous 0 0
  fi
  turn=$((turn + 1))
done
awk '{ wall[$2] += $4; runs[$2]++; if ($3 == 0) passed[$2]++ }
     END { for (s in wall) printf "%-12s %d of %d passed, %.1f s of wall time\n", s, passed[s], runs[s], wall[s];
           if (wall["synchronous"] > 0) printf "budgets over round-synchronous: %.2f\n", wall["budgets"] / wall["synchronous"] }' \
  "$out/runs.txt"
