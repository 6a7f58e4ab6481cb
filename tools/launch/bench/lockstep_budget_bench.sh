#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The demo mission (bringup/demo.yaml, lockstep) with the map update's and the path's budgets
# against the round-synchronous lockstep they replaced, side by side: each pair of runs flies
# the demo once with QUAD_MAP_BUDGET_MS=0 and QUAD_PATH_BUDGET_MS=0 (the clock waits every
# round for the planner, and at every depth frame until its update is out) and once with the
# given budgets (the contracts' 50 and 100 ms by default: the clock runs on while the mapper
# and the planner work), the two taking turns. For each run, from its summary.json:
#   end          the mission's end (success, failed, ...)
#   sim_s        sim time flown
#   flight_s     the flight's wall time (first vehicle state to the last)
#   rtf          sim_s / flight_s
#   map_over     map updates the clock reached the due time of first (the clock waited)
#   path_over    paths the clock reached the due time of first
#   flown_m      path length flown
#   paths        path versions from the planner
#   map_cpu_s    the mapper's CPU time
#   cpu_s        every process's CPU time
# then the median of each column per side, and the median flight time's ratio.
#   tools/launch/bench/lockstep_budget_bench.sh BUILD_DIR [-n PAIRS] [-b MAP_MS] [-p PATH_MS] [-d DOMAIN]
#   (default: 3 pairs, 50 and 100 ms, domain 84)
set -euo pipefail
build=${1:?usage: lockstep_budget_bench.sh BUILD_DIR [-n PAIRS] [-b MAP_MS] [-p PATH_MS] [-d DOMAIN]}
shift
pairs=3
budget=50
path_budget=100
domain=84
while [[ ${1:-} == -* ]]; do
  case "$1" in
    -n) pairs=${2:?-n needs a number of pairs} ;;
    -b) budget=${2:?-b needs milliseconds} ;;
    -p) path_budget=${2:?-p needs milliseconds} ;;
    -d) domain=${2:?-d needs a domain id} ;;
    *)
      echo "lockstep_budget_bench.sh: unknown option $1" >&2
      exit 2
      ;;
  esac
  shift 2
done
source "$(dirname "${BASH_SOURCE[0]}")/../../bench_common.sh"
benchSetup lockstep_budget_bench.sh "$build" quad_lockstep_budget
side="${budget}_${path_budget}"
for ((i = 1; i <= pairs; ++i)); do
  for b in 0_0 "$side"; do
    (
      export QUAD_MAP_BUDGET_MS=${b%_*} QUAD_PATH_BUDGET_MS=${b#*_}
      benchLaunch "$out/run${i}_budget$b" "run $i with budgets $b ms" "$root/bringup/demo.yaml" --no-record
    ) || exit 1
  done
done
python3 - "$out" "$side" <<'EOF'
import glob, json, os, statistics, sys
out, side = sys.argv[1], sys.argv[2]
cols = ["sim_s", "flight_s", "rtf", "map_over", "path_over", "flown_m", "paths", "map_cpu_s", "cpu_s"]
print(f"{'run':<22} {'end':<8} " + " ".join(f"{c:>9}" for c in cols))
rows = {"0_0": [], side: []}
for path in sorted(glob.glob(os.path.join(out, "run*_budget*.json"))):
    s = json.load(open(path))
    b = path.rsplit("budget", 1)[1][:-5]
    flight = s["flight_wall_seconds"] or s["wall_seconds"]
    mapping = s["processes"].get("mapping", {}).get("cpu_seconds")
    cpu = sum(p.get("cpu_seconds") or 0.0 for p in s["processes"].values())
    row = [s["sim_seconds"], flight, s["sim_seconds"] / flight, s["map_overruns"] or 0, s["path_overruns"] or 0,
           s["path_length_m"], s["paths"], mapping or 0.0, cpu]
    rows[b].append(row)
    print(f"{os.path.basename(path)[:-5]:<22} {s['end']:<8} " + " ".join(f"{v:9.2f}" for v in row))
for b, r in rows.items():
    if r:
        med = [statistics.median(c) for c in zip(*r)]
        print(f"{'median, ' + b.replace('_', '+') + ' ms':<22} {'':<8} " + " ".join(f"{v:9.2f}" for v in med))
if rows["0_0"] and rows[side]:
    f0 = statistics.median(r[1] for r in rows["0_0"])
    fb = statistics.median(r[1] for r in rows[side])
    print(f"flight wall time, budgets {side.replace('_', ' and ')} ms over round-synchronous: {fb / f0:.2f}")
EOF
