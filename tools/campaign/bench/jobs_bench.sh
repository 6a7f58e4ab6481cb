#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs per hour of `quad campaign` flying the same runs one at a time (-j 1) and two at a time
# (-j 2), in both layouts (a process per module; the demo's containers composed), side by
# side: N of the benchmark's densest forests (generator seeds 1..N) at a commanded 5 m/s with
# bringup/fast.yaml, each campaign in turn, the whole set R times with the order alternating.
# With -w, ten shipped worlds instead (configs/worlds: the kWorlds below), each flown once with
# bringup/demo.yaml as it ships, recorded. With -s, the same runs also through the Slurm
# cluster $SLURM_CONF names (`--slurm`, a task a run, as many at once as the cluster gives),
# in both layouts.
# For each campaign: its wall time (start-up and every run), runs per hour, and the runs'
# outcomes; then the median runs per hour of each setting.
#   tools/campaign/bench/jobs_bench.sh BUILD_DIR [-n RUNS] [-r ROUNDS] [-d DOMAIN] [-w] [-s]
#   (default: 4 runs, 2 rounds, domains 106 and 107 (Slurm: 106 to 105 + RUNS))
set -euo pipefail
build=${1:?usage: jobs_bench.sh BUILD_DIR [-n RUNS] [-r ROUNDS] [-d DOMAIN] [-w] [-s]}
shift
runs=4 rounds=2 domain=106 slurm=0 worlds=0
while getopts "n:r:d:ws" opt; do
  case $opt in
    n) runs=$OPTARG ;;
    r) rounds=$OPTARG ;;
    d) domain=$OPTARG ;;
    w) worlds=1 ;;
    s) slurm=1 ;;
    *) exit 2 ;;
  esac
done
source "$(dirname "${BASH_SOURCE[0]}")/../../bench_common.sh"
benchSetup jobs_bench.sh "$build" quad_jobs
kWorlds=(benchmark_forest corridor courtyard demo gaps open overhang platform_roof wall window)
if ((worlds)); then
  flown=()
  for w in "${kWorlds[@]}"; do flown+=("$root/configs/worlds/$w.yaml"); done
  flown+=(--manifest "$root/bringup/demo.yaml")
else
  flown=("$root/configs/worlds/benchmark_forest.yaml" --manifest "$root/bringup/fast.yaml"
         --set "world:forest.seed=1..$runs" --set control:follower.max_speed=5)
fi
settings=("1 distributed" "2 distributed" "1 composed" "2 composed")
if ((slurm)); then
  [[ -n ${SLURM_CONF:-} ]] || { echo "jobs_bench.sh: -s: no SLURM_CONF names the cluster" >&2; exit 1; }
  settings+=("slurm distributed" "slurm composed")
fi
for ((r = 1; r <= rounds; ++r)); do
  order=("${settings[@]}")
  if ((r % 2 == 0)); then
    order=()
    for ((i = ${#settings[@]} - 1; i >= 0; --i)); do order+=("${settings[i]}"); done
  fi
  for s in "${order[@]}"; do
    read -r jobs layout <<<"$s"
    dir="$out/round${r}_j${jobs}_$layout"
    how=(-j "$jobs")
    [[ $jobs == slurm ]] && how=(--slurm)
    start=$(date +%s.%N)
    "$quad" campaign "${flown[@]}" --layout "$layout" "${how[@]}" --domain "$domain" --log-dir "$dir" \
      > "$dir.out" 2>&1 || true
    end=$(date +%s.%N)
    python3 -c "print($end - $start)" > "$dir.wall"
    [[ -f $dir/campaign.json ]] || { echo "round $r, -j $jobs $layout, wrote no campaign.json: see $dir.out" >&2; exit 1; }
  done
done
python3 - "$out" <<'EOF_PY'
import glob, json, os, statistics, sys
out = sys.argv[1]
per = {}
print(f"{'campaign':<28} {'runs':>4} {'ok':>3} {'wall_s':>8} {'runs/h':>7}")
for wall in sorted(glob.glob(f"{out}/round*.wall")):
    name = os.path.basename(wall)[:-5]
    j = json.load(open(f"{out}/{name}/campaign.json"))
    w = float(open(wall).read())
    rate = 3600 * len(j["runs"]) / w
    setting = name.split("_", 1)[1]
    per.setdefault(setting, []).append(rate)
    print(f"{name:<28} {len(j['runs']):>4} {j['succeeded']:>3} {w:>8.1f} {rate:>7.0f}")
print("median runs per hour:")
for setting, rates in per.items():
    print(f"  {setting:<16} {statistics.median(rates):>6.0f}")
EOF_PY
