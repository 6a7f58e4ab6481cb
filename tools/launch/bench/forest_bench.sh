#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fast flight in the benchmark forests of Loquercio et al. ("Learning high-speed flight in the
# wild", Science Robotics 2021): trees about 0.6 m thick placed at random without overlap over a
# 30 x 60 m area, a 40 m line from start to goal, one tree per 49, 36 or 25 m^2, each forest
# flown at each commanded speed, in lockstep, on the estimate.
#
#   tools/launch/bench/forest_bench.sh BUILD_DIR [-d "49 36 25"] [-v "3 5 7 10"] [-n 10] [-t 600] [-j 1] [-l LAYOUT]
#
# -d: square metres per tree; -v: follower.max_speed [m/s]; -n: forests (the forest generator's
# seeds 1..N) a density; -t: the wall timeout of one run [s]; -j: runs flown at once; -l:
# distributed (default) or composed (the same flights, in less time: docs/launch.md). The grid
# is one `quad campaign --file forest_grid.yaml` (its axes narrowed by the options);
# forest_grid.py prints it (success rate, average and top speed, time to goal, flown length
# over the known-map optimum, closest approach) and writes grid.json and grid.svg in the runs'
# folder.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../../bench_common.sh"

build=${1:?usage: forest_bench.sh BUILD_DIR [-d DENSITIES] [-v SPEEDS] [-n FORESTS] [-t SECONDS] [-j JOBS] [-l LAYOUT]}
shift
densities="49 36 25" speeds="3 5 7 10" forests=10 timeout=600 jobs=1 layout=distributed
while getopts "d:v:n:t:j:l:" opt; do
  case $opt in
    d) densities=$OPTARG ;;
    v) speeds=$OPTARG ;;
    n) forests=$OPTARG ;;
    t) timeout=$OPTARG ;;
    j) jobs=$OPTARG ;;
    l) layout=$OPTARG ;;
    *) exit 2 ;;
  esac
done
benchSetup forest_bench.sh "$build" quad_forest

# trees per m^2 to six places: the axis's values, which forest_grid.py turns back into m^2 per tree
per_m2=$(python3 -c "import sys; print(','.join(f'{1/float(d):.6f}' for d in sys.argv[1:]))" $densities)
"$quad" campaign --file "$root/tools/launch/bench/forest_grid.yaml" \
  --set "world:forest.density=$per_m2" --set "control:follower.max_speed=${speeds// /,}" \
  --set "world:forest.seed=1..$forests" --wall-timeout "$timeout" -j "$jobs" --layout "$layout" \
  --log-dir "$out/runs" --json "$out/campaign.json" || true
python3 "$root/tools/launch/bench/forest_grid.py" "$out/campaign.json"
