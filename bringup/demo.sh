#!/usr/bin/env bash
# The demo the README runs: the plant and control participants fly a mission in real time
# (twice the wall clock) on a private DDS domain. An operator, played by `quad topic pub`,
# gives the goal and a path; the controller arms, takes off, flies the path, holds at the
# goal, and lands when the operator says so; the plant reports collisions. Until the mapping and planning modules land, the path
# is the operator's rather than the planner's.
#   bringup/demo.sh BUILD_DIR
set -euo pipefail

build=${1:?usage: bringup/demo.sh BUILD_DIR}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
quad="$build/tools/quad/quad"
plant="$build/modules/plant/node/quad_plant_node"
control="$build/modules/control/node/quad_control_node"
for program in "$quad" "$plant" "$control"; do
  [[ -x $program ]] || { echo "demo: $program not built" >&2; exit 1; }
done

export QUAD_DOMAIN_ID=${QUAD_DOMAIN_ID:-42}
export QUAD_LOG_DIR=${QUAD_LOG_DIR:-$build/demo-logs/$(date +%Y%m%d-%H%M%S)}
mkdir -p "$QUAD_LOG_DIR"
echo "demo: domain $QUAD_DOMAIN_ID, logs in $QUAD_LOG_DIR"

pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT

"$control" --config "$root/configs/control.yaml" 2>"$QUAD_LOG_DIR/control.out" &
pids+=($!)
"$quad" topic pub quad/planning/goal '{goal_id: 1, p_W: {x: 20, y: 5, z: 3}, tolerance: 0.3}' \
  >/dev/null &
pids+=($!)
"$quad" topic pub quad/planning/path \
  '{version: 1, goal_id: 1, status: PLAN_OK, waypoints_W: [{x: 0, y: 0, z: 2}, {x: 10, y: 0, z: 2}, {x: 20, y: 5, z: 3}]}' \
  --count 60 --rate 2 >/dev/null &
pids+=($!)

# Progress: the controller's mode changes as they happen.
"$quad" topic echo quad/control/status --json 2>/dev/null > >(
  awk -F'"mode":"' '{split($2, a, "\""); if (a[1] != last) { print "demo: control mode " a[1]; last = a[1] } fflush() }'
) &
status_pid=$!
pids+=($status_pid)

echo "demo: flying (sim time at 2x real time)"
"$plant" --config "$root/bringup/demo/plant.yaml" 2>"$QUAD_LOG_DIR/plant.out" &
plant_pid=$!
pids+=($plant_pid)

# Waits up to $2 seconds for the control log to say $1.
await() {
  for _ in $(seq 1 $(($2 * 10))); do
    grep -q "$1" "$QUAD_LOG_DIR/control.out" && return 0
    kill -0 "$plant_pid" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}
if await "goal reached" 60; then
  "$quad" topic pub quad/system/command '{command_id: 2, kind: COMMAND_LAND}' >/dev/null
  await "LAND -> IDLE: landed" 30 || true
fi
sleep 0.3  # let the last mode change print
kill "$status_pid" 2>/dev/null || true
kill -INT "$plant_pid" 2>/dev/null || true
wait "$plant_pid" || true

result=$(grep -h "run ended" "$QUAD_LOG_DIR/plant.out" | sed 's/.*run ended: //')
final=$(grep -h "final state" "$QUAD_LOG_DIR/plant.out" | sed 's/.*final state //')
echo "demo: plant: $result"
echo "demo: plant: $final"
if grep -q "goal reached" "$QUAD_LOG_DIR/control.out" && grep -q "LAND -> IDLE: landed" "$QUAD_LOG_DIR/control.out" &&
  grep -q "collisions 0," "$QUAD_LOG_DIR/plant.out"; then
  echo "demo: mission complete: goal reached, landed, no collision"
else
  echo "demo: mission FAILED (see $QUAD_LOG_DIR)" >&2
  exit 1
fi
