#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The demo mission (bringup/demo.yaml, lockstep, recorded as `quad launch` records it) with a
# process per module against its containers composed (--layout composed: every module in one
# process, the manifest's one container), side by side: each pair flies
# the demo once each way, the two taking turns, with one seed. For each run, from its
# summary.json:
#   end        the mission's end (success, failed, ...)
#   sim_s      sim time flown
#   wall_s     the run's wall time, start-up included
#   flight_s   the flight's wall time (first vehicle state to the last)
#   rtf        sim_s / wall_s, as the summary gives it
#   cpu_s      every process's CPU time, the launcher's included
# then each process's (or container's) CPU seconds per sim second, the median of each column
# per layout, and the median wall time's ratio. Then, per run, whom the lockstep clock waited
# for and how long (the plant's last word in its log: docs/runtime.md#lockstep) and the
# mapper's wall time from a cloud to its changes (MapStats.insert_time_s in the recording,
# median and 90th percentile), with their medians per layout.
#   tools/launch/bench/layout_bench.sh BUILD_DIR [-n PAIRS] [-s SEED] [-d DOMAIN]
#   (default: 5 pairs, seed 1, domain 85)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../../bench_common.sh"
build=${1:?usage: layout_bench.sh BUILD_DIR [-n PAIRS] [-s SEED] [-d DOMAIN]}
shift
pairs=5
seed=1
domain=85
benchPairOptions layout_bench.sh "$@"
benchSetup layout_bench.sh "$build" quad_layout
for ((i = 1; i <= pairs; ++i)); do
  for layout in distributed composed; do
    benchLaunch "$out/run${i}_$layout" "run $i, $layout," "$root/bringup/demo.yaml" --layout "$layout" --seed "$seed"
  done
done
for run in "$out"/run*_*/; do
  "$quad" bag echo "$run/recording.mcap" --topics quad/mapping/stats --json > "${run%/}.stats.jsonl" 2>/dev/null || true
done
python3 - "$out" <<'EOF_PY'
import glob, json, os, statistics, sys
out = sys.argv[1]
cols = ["sim_s", "wall_s", "flight_s", "rtf", "cpu_s"]
print(f"{'run':<18} {'end':<8} " + " ".join(f"{c:>8}" for c in cols) + "   CPU s per sim s")
rows = {"distributed": [], "composed": []}
per_process = {"distributed": {}, "composed": {}}
for path in sorted(glob.glob(os.path.join(out, "run*_*.json"))):
    s = json.load(open(path))
    layout = path.rsplit("_", 1)[1][:-5]
    cpu = sum(p.get("cpu_seconds") or 0.0 for p in s["processes"].values())
    row = [s["sim_seconds"], s["wall_seconds"], s["flight_wall_seconds"] or s["wall_seconds"], s["real_time_factor"], cpu]
    rows[layout].append(row)
    shares = {name: (p.get("cpu_seconds") or 0.0) / s["sim_seconds"] for name, p in s["processes"].items()}
    for name, v in shares.items():
        per_process[layout].setdefault(name, []).append(v)
    print(f"{os.path.basename(path)[:-5]:<18} {s['end']:<8} " + " ".join(f"{v:8.2f}" for v in row) + "   " +
          ", ".join(f"{n} {v:.3f}" for n, v in shares.items()))
for layout, r in rows.items():
    if r:
        med = [statistics.median(c) for c in zip(*r)]
        print(f"{'median, ' + layout:<18} {'':<8} " + " ".join(f"{v:8.2f}" for v in med) + "   " +
              ", ".join(f"{n} {statistics.median(v):.3f}" for n, v in per_process[layout].items()))
if rows["distributed"] and rows["composed"]:
    d = statistics.median(r[1] for r in rows["distributed"])
    c = statistics.median(r[1] for r in rows["composed"])
    print(f"wall time, composed over distributed: {c / d:.2f}")

# Whom the clock waited for: "lockstep: the clock waited in N rounds, T s of wall time in all:
# for mapping 3.351 s in 417 rounds, planning ..."; and the mapper's time per cloud.
waited = {"distributed": {}, "composed": {}}
print(f"\n{'run':<18} {'insert ms':>9} {'p90':>6}   the clock waited for [s]")
for run in sorted(glob.glob(os.path.join(out, "run*_*/"))):
    name = os.path.basename(run.rstrip("/"))
    layout = name.rsplit("_", 1)[1]
    line = ""
    for log in glob.glob(os.path.join(run, "*.log")):
        for text in open(log, errors="replace"):
            if "lockstep: the clock waited in" in text:
                line = text.split("lockstep: ", 1)[1].strip()
    each = {}
    if ": for " in line:
        for part in line.split(": for ", 1)[1].split(", "):
            who, rest = part.split(" ", 1)
            each[who] = float(rest.split(" s in ")[0])
    for who, s in each.items():
        waited[layout].setdefault(who, []).append(s)
    times = []
    stats = run.rstrip("/") + ".stats.jsonl"
    if os.path.exists(stats):
        for text in open(stats):
            m = json.loads(text)["message"]
            if m["points"] > 0:
                times.append(m["insert_time_s"] * 1e3)
    times.sort()
    med = f"{statistics.median(times):9.2f} {times[int(0.9 * len(times))]:6.2f}" if times else f"{'-':>9} {'-':>6}"
    print(f"{name:<18} {med}   " + ", ".join(f"{w} {s:.2f}" for w, s in each.items()))
for layout, w in waited.items():
    if w:
        print(f"{'median, ' + layout:<18} {'':>16}   " + ", ".join(f"{who} {statistics.median(s):.2f}" for who, s in w.items()))
EOF_PY
