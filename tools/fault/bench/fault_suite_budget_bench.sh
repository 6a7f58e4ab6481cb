#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The fault suite (tests/scenarios/*.yaml, as `ctest -L fault` runs it) with the map update's and
# the path's budgets as they ship against the round-synchronous lockstep they replaced
# (QUAD_MAP_BUDGET_MS=0 QUAD_PATH_BUDGET_MS=0: the clock waits every round for the planner, and
# at every depth frame until its update is out), side by side: each scenario runs once each way,
# the order turned at every scenario so that neither side always goes first. For each run:
#   scenario, its mode (the scenario's `mode:`, else its manifest's), side, its exit status
#   (0: every expectation met) and its wall time,
# then each side's passes and total wall time, for the lockstep scenarios, the real-time ones
# (no lockstep: the same both ways) and all, and the ratios of the totals.
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
source "$(dirname "${BASH_SOURCE[0]}")/../../bench_common.sh"
benchSetup fault_suite_budget_bench.sh "$build" quad_fault_budget
scenarios=("$@")
((${#scenarios[@]})) || scenarios=("$root"/tests/scenarios/*.yaml)
modeOf() {  # scenario: its mode, or its manifest's
  local mode manifest
  mode=$(sed -n 's/^mode:[[:space:]]*\([a-z]*\).*/\1/p' "$1")
  if [[ -z $mode ]]; then
    manifest=$(sed -n 's/^manifest:[[:space:]]*\([^[:space:]#]*\).*/\1/p' "$1")
    mode=$(sed -n 's/^mode:[[:space:]]*\([a-z]*\).*/\1/p' "$(dirname "$1")/$manifest")
  fi
  echo "${mode:-lockstep}"
}
runOne() {  # scenario side [VAR=VALUE...]: the run with those budgets, the shipped ones without
  local scenario=$1 side=$2 name dir start rc=0
  shift 2
  name=$(basename "$scenario" .yaml)
  dir="$out/$name.$side"
  start=$EPOCHREALTIME
  env -u QUAD_MAP_BUDGET_MS -u QUAD_PATH_BUDGET_MS "$@" "$quad" fault "$scenario" --domain "$domain" -q \
    --no-report --wall-timeout 280 --log-dir "$dir" > "$dir.out" 2>&1 || rc=$?
  echo "$name $(modeOf "$scenario") $side $rc $(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }')" |
    tee -a "$out/runs.txt"
}
synchronous=(QUAD_MAP_BUDGET_MS=0 QUAD_PATH_BUDGET_MS=0)
turn=0
for s in "${scenarios[@]}"; do
  if ((turn % 2 == 0)); then
    runOne "$s" synchronous "${synchronous[@]}"
    runOne "$s" budgets
  else
    runOne "$s" budgets
    runOne "$s" synchronous "${synchronous[@]}"
  fi
  turn=$((turn + 1))
done
awk '{ for (g = 0; g < 2; ++g) { k = (g ? "all" : $2) SUBSEP $3; wall[k] += $5; runs[k]++; passed[k] += ($4 == 0) } }
     END { n = split("lockstep realtime all", groups, " ")
           for (i = 1; i <= n; ++i) {
             sy = groups[i] SUBSEP "synchronous"; bu = groups[i] SUBSEP "budgets"
             if (!runs[sy]) continue
             printf "%-9s round-synchronous %d of %d passed, %.1f s; budgets %d of %d passed, %.1f s; ratio %.2f\n",
                    groups[i], passed[sy], runs[sy], wall[sy], passed[bu], runs[bu], wall[bu], wall[bu] / wall[sy] } }' \
  "$out/runs.txt"
