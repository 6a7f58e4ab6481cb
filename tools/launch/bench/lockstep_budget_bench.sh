#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The demo mission (bringup/demo.yaml, lockstep) with the map update's budget against the
# round-synchronous lockstep it replaced, side by side: each pair of runs flies the demo once
# with QUAD_MAP_BUDGET_MS=0 (the clock waits at every depth frame until its update is out)
# and once with the given budget (the contract's 50 ms by default: the clock runs on while
# the mapper works), the two taking turns. For each run, from its summary.json:
#   end          the mission's end (success, failed, ...)
#   sim_s        sim time flown
#   flight_s     the flight's wall time (first vehicle state to the last)
#   rtf          sim_s / flight_s
#   overruns     map updates the clock reached the due time of first (the clock waited)
#   flown_m      path length flown
#   paths        path versions from the planner
#   map_cpu_s    the mapper's CPU time
# then the median of each column per budget, and the median flight time's ratio.
#   tools/launch/bench/lockstep_budget_bench.sh BUILD_DIR [-n PAIRS] [-b BUDGET_MS] [-d DOMAIN]
#   (default: 3 pairs, 50 ms, domain 84)
set -euo pipefail
build=${1:?usage: lockstep_budget_bench.sh BUILD_DIR [-n PAIRS] [-b BUDGET_MS] [-d DOMAIN]}
shift
pairs=3
budget=50
domain=84
while [[ ${1:-} == -* ]]; do
  case "$1" in
    -n) pairs=${2:?-n needs a number of pairs} ;;
    -b) budget=${2:?-b needs milliseconds} ;;
    -d) domain=${2:?-d needs a domain id} ;;
    *)
      echo "lockstep_budget_bench.sh: unknown option $1" >&2
      exit 2
      ;;
  esac
  shift 2
done
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
quad="$build/tools/quad/quad"
[[ -x $quad ]] || { echo "lockstep_budget_bench.sh: no $quad: build first" >&2; exit 1; }
out=$(mktemp -d /tmp/quad_lockstep_budget_XXXXXX)
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "runs in $out"
for ((i = 1; i <= pairs; ++i)); do
  for b in 0 "$budget"; do
    dir="$out/run${i}_budget$b"
    QUAD_MAP_BUDGET_MS=$b "$quad" launch "$root/bringup/demo.yaml" --quiet --no-record \
      --domain "$domain" --log-dir "$dir" --summary "$dir.json" > "$dir.out" 2>&1 || true
    [[ -f $dir.json ]] || { echo "run $i with a $b ms budget wrote no summary: see $dir.out" >&2; exit 1; }
  done
done
python3 - "$out" "$budget" <<'EOF'
import glob, json, os, statistics, sys
out, budget = sys.argv[1], sys.argv[2]
cols = ["sim_s", "flight_s", "rtf", "overruns", "flown_m", "paths", "map_cpu_s"]
print(f"{'run':<18} {'end':<8} " + " ".join(f"{c:>9}" for c in cols))
rows = {"0": [], budget: []}
for path in sorted(glob.glob(os.path.join(out, "run*_budget*.json"))):
    s = json.load(open(path))
    b = path.rsplit("budget", 1)[1][:-5]
    flight = s["flight_wall_seconds"] or s["wall_seconds"]
    mapping = s["processes"].get("mapping", {}).get("cpu_seconds")
    row = [s["sim_seconds"], flight, s["sim_seconds"] / flight, s["map_overruns"] or 0, s["path_length_m"],
           s["paths"], mapping or 0.0]
    rows[b].append(row)
    print(f"{os.path.basename(path)[:-5]:<18} {s['end']:<8} " + " ".join(f"{v:9.2f}" for v in row))
for b, r in rows.items():
    if r:
        med = [statistics.median(c) for c in zip(*r)]
        print(f"{'median, ' + b + ' ms':<18} {'':<8} " + " ".join(f"{v:9.2f}" for v in med))
if rows["0"] and rows[budget]:
    f0 = statistics.median(r[1] for r in rows["0"])
    fb = statistics.median(r[1] for r in rows[budget])
    print(f"flight wall time, {budget} ms budget over round-synchronous: {fb / f0:.2f}")
EOF
