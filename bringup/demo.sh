#!/usr/bin/env bash
# The demo the README runs. Until the flight modules land, it is a smoke exchange between two
# processes on a private DDS domain: `quad topic pub` sends operator commands and
# `quad topic echo` prints them, decoded from the IDL; `quad topic list` shows the traffic.
#   bringup/demo.sh BUILD_DIR
set -euo pipefail

build=${1:?usage: bringup/demo.sh BUILD_DIR}
quad="$build/tools/quad/quad"
[[ -x $quad ]] || { echo "demo: $quad not built" >&2; exit 1; }

export QUAD_DOMAIN_ID=${QUAD_DOMAIN_ID:-42}
echo "demo: domain $QUAD_DOMAIN_ID"

"$quad" topic echo quad/system/command --count 3 --timeout 30 &
echo_pid=$!
trap 'kill $echo_pid 2>/dev/null || true' EXIT

# What is on the domain now: the echo's reader.
"$quad" topic list --wait 1
"$quad" topic pub quad/system/command '{command_id: 1, kind: COMMAND_TAKEOFF, altitude: 2.0}' \
  --count 3 --rate 2
wait $echo_pid
trap - EXIT
echo "demo: the commands crossed between two processes"
