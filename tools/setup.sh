#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Sets up a Debian 12 machine for quad and runs one of its two jobs:
#   tools/setup.sh demo [quad launch options]   install, configure, build (release) and fly
#                                              the demo mission (bringup/demo.yaml)
#   tools/setup.sh test   install, configure, build (ci preset, -Werror) and run every test
# As root, missing Debian packages are installed with apt-get; otherwise the exact
# apt-get line is printed and the script stops.
set -euo pipefail

job=${1:-}
shift || true
case "$job" in
  demo | test) ;;
  *)
    echo "usage: tools/setup.sh demo|test" >&2
    exit 2
    ;;
esac

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

# Everything quad needs from Debian 12, toolchain included (a fresh system has no compiler).
packages=(
  build-essential cmake ninja-build ccache pkg-config git iproute2 iptables procps python3
  openssh-client openssh-server man-db
  default-jre-headless
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  cyclonedds-dev cyclonedds-tools
  libeigen3-dev liboctomap-dev libmrpt-poses-dev libmrpt-math-dev
  libspdlog-dev libfmt-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev liblz4-dev libzstd-dev libssl-dev openssl libboost-dev
  nodejs chromium
  slurmctld slurmd slurm-client munge   # the single-node cluster the campaign's Slurm test starts
)
# npm for the test that reads recordings with Foxglove's own MCAP reader; a Node.js from
# elsewhere (NodeSource) brings its own npm and conflicts with Debian's.
command -v npm > /dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
if ((${#missing[@]} > 0)); then
  if [[ $(id -u) -eq 0 ]]; then
    echo "setup: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}"
  else
    echo "setup: missing Debian packages. Run as root, or install them with:" >&2
    echo "  sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

# ccache keeps rebuilds of a fresh clone cheap.
export CCACHE_DIR=${CCACHE_DIR:-$HOME/.cache/ccache}
# Paths below the checkout are hashed relative to it, so another clone reuses the cache.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$root}
# The ci preset compiles with debug information, for which ccache also hashes the working
# directory unless told not to: every new clone would then rebuild from scratch. Its objects'
# debug information may name the clone they were first built in.
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}

if [[ $job == test ]]; then
  cmake --preset ci
  cmake --build --preset ci
  ctest --preset ci
else
  cmake --preset release
  cmake --build --preset release
  # The four modules fly the demo mission in lockstep; the run's logs and summary land in
  # log/demo-<time>-<pid>/.
  exec "$root/build/release/tools/quad/quad" launch "$root/bringup/demo.yaml" "$@"
fi
