#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# How fast the lockstep demo could go on this machine, from below: three stacks side by side,
# taking turns, each a run of `quad launch` in lockstep on the demo's world and module configs:
#   loop          the control loop alone: plant, estimator and controller (the launcher's
#                 observer scoring the run, as in every run); no planner, so the vehicle takes
#                 off and hovers for SIM_S seconds of sim time, and the mission ends unfinished
#   loop+display  the same, with the display participant and the recorder as the demo runs them
#   demo          bringup/demo.yaml as it ships (the mapper and the planner too), to its goal
# The first two are parts of the third: what they cost, the demo cannot cost less, so their
# pace bounds the demo's. For each run, from its summary.json:
#   end          the mission's end (unfinished for the two hovering stacks, by design)
#   sim_s        sim time flown
#   flight_s     the flight's wall time (first vehicle state to the last)
#   rtf          sim_s / flight_s
#   cpu/sim_s    every process's CPU time per second of sim time [core-seconds]
#   waits/round  every process's waits (voluntary context switches) per 4 ms round
# then the median of each column per stack, and each stack's processes' CPU per sim second.
#   tools/launch/bench/loop_ceiling_bench.sh BUILD_DIR [-n RUNS] [-t SIM_S] [-d DOMAIN]
#   (default: 3 runs of each, 40 s of sim time hovering, domain 85)
set -euo pipefail
build=${1:?usage: loop_ceiling_bench.sh BUILD_DIR [-n RUNS] [-t SIM_S] [-d DOMAIN]}
shift
runs=3
sim_s=40
domain=85
while [[ ${1:-} == -* ]]; do
  case "$1" in
    -n) runs=${2:?-n needs a number of runs} ;;
    -t) sim_s=${2:?-t needs seconds of sim time} ;;
    -d) domain=${2:?-d needs a domain id} ;;
    *)
      echo "loop_ceiling_bench.sh: unknown option $1" >&2
      exit 2
      ;;
  esac
  shift 2
done
source "$(dirname "${BASH_SOURCE[0]}")/../../bench_common.sh"
benchSetup loop_ceiling_bench.sh "$build" quad_loop_ceiling

# The hovering stacks: the demo's world, configs, vehicle and mission, without the mapper and
# the planner (and the plant's lockstep waits for them), stopped after SIM_S of sim time.
hover_manifest() {
  local name=$1 display=$2
  cat <<EOF
name: $name
world: $root/configs/worlds/demo.yaml
mode: lockstep
state: estimate
transport: udp
modules:
EOF
  if [[ $display == yes ]]; then
    cat <<EOF
  display:
    config: $root/configs/display.yaml
    set: {world: "\${world}", state.source: "\${state}"}
EOF
  fi
  cat <<EOF
  estimation:
    config: $root/configs/estimation.yaml
  control:
    config: $root/configs/control.yaml
    set: {state.source: "\${state}"}
    needs: [quad/estimation/state]
  plant:
    config: $root/configs/plant.yaml
    set:
      world: "\${world}"
      sim.mode: "\${mode}"
      sim.seed: "\${seed}"
      sim.duration: $sim_s
      state.source: "\${state}"
    needs: [quad/control/actuators, quad/sim/lockstep]
    ends_run: true
mission:
  tolerance: 0.4
  land: true
  timeout: 200.0
  vehicle: $root/configs/vehicles/x500.yaml
EOF
}
hover_manifest loop no > "$out/loop.yaml"
hover_manifest loop_display yes > "$out/loop_display.yaml"

for ((i = 1; i <= runs; ++i)); do
  for stack in loop loop_display demo; do
    case $stack in
      loop) args=("$out/loop.yaml" --no-record) ;;
      loop_display) args=("$out/loop_display.yaml") ;;
      demo) args=("$root/bringup/demo.yaml") ;;
    esac
    # The hovering stacks end unfinished (exit 1) by design: their summary is what counts.
    benchLaunch "$out/run${i}_$stack" "run $i of $stack" "${args[@]}" --no-report
  done
done

python3 - "$out" <<'EOF'
import glob, json, os, statistics, sys
out = sys.argv[1]
stacks = ["loop", "loop_display", "demo"]
cols = ["sim_s", "flight_s", "rtf", "cpu/sim_s", "waits/round"]
print(f"{'run':<20} {'end':<11} " + " ".join(f"{c:>11}" for c in cols))
rows = {s: [] for s in stacks}
per = {s: {} for s in stacks}
for stack in stacks:
    for path in sorted(glob.glob(os.path.join(out, f"run*_{stack}.json"))):
        s = json.load(open(path))
        sim, flight = s["sim_seconds"], s["flight_wall_seconds"]
        procs = s["processes"]
        cpu = sum(p.get("cpu_seconds") or 0.0 for p in procs.values())
        waits = sum(p.get("waits") or 0 for p in procs.values())
        row = [sim, flight, sim / flight, cpu / sim, waits / (sim / 0.004)]
        rows[stack].append(row)
        for name, p in procs.items():
            per[stack].setdefault(name, []).append((p.get("cpu_seconds") or 0.0) / sim)
        print(f"{os.path.basename(path)[:-5]:<20} {s['end']:<11} " + " ".join(f"{v:11.3f}" for v in row))
for stack in stacks:
    if rows[stack]:
        med = [statistics.median(c) for c in zip(*rows[stack])]
        print(f"{'median, ' + stack:<20} {'':<11} " + " ".join(f"{v:11.3f}" for v in med))
print("CPU per sim second, medians [core-seconds]:")
for stack in stacks:
    print(f"  {stack:<13} " + ", ".join(f"{n} {statistics.median(v):.3f}" for n, v in sorted(per[stack].items())))
EOF
