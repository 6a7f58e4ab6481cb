#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fast flight in the benchmark forests of Loquercio et al. ("Learning high-speed flight in the
# wild", Science Robotics 2021): trees about 0.6 m thick placed at random without overlap over a
# 30 x 60 m area, a 40 m line from start to goal, one tree per 49, 36 or 25 m^2, each forest
# flown at each commanded speed, in lockstep, on the estimate.
#
#   tools/launch/bench/forest_bench.sh BUILD_DIR [-d "49 36 25"] [-v "3 5 7 10"] [-n 10] [-t 600]
#
# -d: square metres per tree; -v: follower.max_speed [m/s]; -n: forests (the forest generator's
# seeds 1..N) a density; -t: the wall timeout of one run [s]. The forests are
# configs/worlds/benchmark_forest.yaml with its seed and density changed; the manifest is
# bringup/fast.yaml with its speed changed (below 5 m/s, with control.yaml's acceleration and jerk). Each
# cell of density x speed is one `quad campaign` of the N forests; forest_grid.py prints the
# grid (success rate, average and top speed, time to goal, flown length over the known-map
# optimum, closest approach) and writes grid.json and grid.svg in the runs' folder.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../../bench_common.sh"

build=${1:?usage: forest_bench.sh BUILD_DIR [-d DENSITIES] [-v SPEEDS] [-n FORESTS] [-t SECONDS]}
shift
densities="49 36 25" speeds="3 5 7 10" forests=10 timeout=600
while getopts "d:v:n:t:" opt; do
  case $opt in
    d) densities=$OPTARG ;;
    v) speeds=$OPTARG ;;
    n) forests=$OPTARG ;;
    t) timeout=$OPTARG ;;
    *) exit 2 ;;
  esac
done
benchSetup forest_bench.sh "$build" quad_forest

world="$root/configs/worlds/benchmark_forest.yaml"
grep -q "type: forest, seed: 1, .* density: 0.04," "$world" || { echo "forest_bench.sh: $world: no forest of seed 1 and density 0.04 to draw the others from" >&2; exit 1; }
for d in $densities; do
  for s in $(seq 1 "$forests"); do
    sed -e "s/type: forest, seed: 1,/type: forest, seed: $s,/" -e "s/density: 0.04,/density: $(python3 -c "print(1/$d)"),/" \
      "$world" >"$out/forest${d}_s$s.yaml"
  done
done

manifest="$root/bringup/fast.yaml"
for v in $speeds; do
  slow=()
  if python3 -c "import sys; sys.exit(0 if $v < 5 else 1)"; then
    # below 5 m/s, control.yaml's own acceleration and jerk
    slow=(-e "s/, follower.max_acceleration: [0-9.]+, follower.max_jerk: [0-9.]+//")
  fi
  sed -E -e "s|\.\./|$root/|g" -e "s/follower.max_speed: [0-9.]+/follower.max_speed: $v/" "${slow[@]}" \
    "$manifest" >"$out/speed$v.yaml"
  grep -qE "follower.max_speed: $v[,}]" "$out/speed$v.yaml" || { echo "forest_bench.sh: $manifest: no follower.max_speed to change" >&2; exit 1; }
done

for d in $densities; do
  for v in $speeds; do
    worlds=()
    for s in $(seq 1 "$forests"); do worlds+=("$out/forest${d}_s$s.yaml"); done
    echo "== one tree per $d m^2, $v m/s"
    "$quad" campaign "${worlds[@]}" --manifest "$out/speed$v.yaml" --wall-timeout "$timeout" \
      --json "$out/cell_${d}_$v.json" --log-dir "$out/cell_${d}_$v" || true
  done
done
python3 "$root/tools/launch/bench/forest_grid.py" "$out" "$densities" "$speeds"
