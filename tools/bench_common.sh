# SPDX-License-Identifier: BSD-3-Clause
# Sourced by the whole-stack bench scripts (tools/*/bench/*.sh), not run:
#   benchSetup SCRIPT BUILD_DIR PREFIX
# sets `root` (the source tree), `quad` (the built command line, refused with SCRIPT's name when
# it is not built) and `out` (a new directory /tmp/PREFIX_XXXXXX for the runs), and says which
# machine runs them and where the runs go.
benchSetup() {
  local script=$1 build=$2 prefix=$3
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  quad="$build/tools/quad/quad"
  [[ -x $quad ]] || { echo "$script: no $quad: build first" >&2; exit 1; }
  out=$(mktemp -d "/tmp/${prefix}_XXXXXX")
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
  echo "runs in $out"
}

#   benchPairOptions SCRIPT "$@"
# reads the options of the benches that fly pairs of runs: -n PAIRS, -s SEED and -d DOMAIN into
# `pairs`, `seed` and `domain` (the caller sets their defaults first); any other option is
# refused with SCRIPT's name.
benchPairOptions() {
  local script=$1
  shift
  while [[ ${1:-} == -* ]]; do
    case "$1" in
      -n) pairs=${2:?-n needs a number of pairs} ;;
      -s) seed=${2:?-s needs a seed} ;;
      -d) domain=${2:?-d needs a domain id} ;;
      *)
        echo "$script: unknown option $1" >&2
        exit 2
        ;;
    esac
    shift 2
  done
}

#   benchLaunch DIR WHAT LAUNCH_ARGS...
# flies one run: `quad launch LAUNCH_ARGS` quietly on `domain`, its logs in DIR, its summary in
# DIR.json and its output in DIR.out. A run that fails still counts (its summary says how it
# ended); one that wrote no summary stops the bench, naming WHAT ("run 2, indoor").
benchLaunch() {
  local dir=$1 what=$2
  shift 2
  "$quad" launch "$@" --quiet --domain "$domain" --log-dir "$dir" --summary "$dir.json" > "$dir.out" 2>&1 || true
  [[ -f $dir.json ]] || { echo "$what wrote no summary: see $dir.out" >&2; exit 1; }
}
