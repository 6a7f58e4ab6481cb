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
