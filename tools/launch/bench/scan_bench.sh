#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The plant's cost in a real scanned map against the demo's, side by side: each pair flies the
# demo (bringup/demo.yaml: primitives and a forest) and the indoor mission down the scanned
# office's corridor (bringup/indoor.yaml in configs/worlds/geb079.yaml: 185,673 voxels of
# 0.08 m), taking turns, lockstep, one seed. For each run, from its summary.json: the end, sim
# and wall seconds, and the plant's CPU seconds per sim second; then the medians per mission
# and the plant's ratio, scan over demo.
#   tools/launch/bench/scan_bench.sh BUILD_DIR [-n PAIRS] [-s SEED] [-d DOMAIN]
#   (default: 3 pairs, seed 1, domain 86)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../../bench_common.sh"
build=${1:?usage: scan_bench.sh BUILD_DIR [-n PAIRS] [-s SEED] [-d DOMAIN]}
shift
pairs=3
seed=1
domain=86
benchPairOptions scan_bench.sh "$@"
benchSetup scan_bench.sh "$build" quad_scan
for ((i = 1; i <= pairs; ++i)); do
  for mission in demo indoor; do
    benchLaunch "$out/run${i}_$mission" "run $i, $mission," "$root/bringup/$mission.yaml" --seed "$seed" --no-record
  done
done
python3 - "$out" <<'EOF_PY'
import glob, json, os, statistics, sys
out = sys.argv[1]
print(f"{'run':<14} {'end':<8} {'sim_s':>7} {'wall_s':>7} {'plant CPU s / sim s':>20}")
plant = {"demo": [], "indoor": []}
for path in sorted(glob.glob(os.path.join(out, "run*_*.json"))):
    s = json.load(open(path))
    mission = path.rsplit("_", 1)[1][:-5]
    share = (s["processes"]["plant"].get("cpu_seconds") or 0.0) / s["sim_seconds"]
    plant[mission].append(share)
    print(f"{os.path.basename(path)[:-5]:<14} {s['end']:<8} {s['sim_seconds']:7.1f} {s['wall_seconds']:7.1f} {share:20.3f}")
d = statistics.median(plant["demo"])
i = statistics.median(plant["indoor"])
print(f"median plant CPU s per sim s: demo {d:.3f}, scanned office {i:.3f}: {i / d:.2f} x the demo's")
EOF_PY
