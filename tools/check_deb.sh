#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Checks a quad Debian package on a clean Debian 12: bootstraps a minimal bookworm root,
# installs the package there with apt (which must find every dependency the package
# declares, and nothing of the build machine is there to hide a missing one), and flies the
# demo from the installed files, in a chroot. As root; takes a few minutes and needs the
# Debian mirror this machine's apt uses.
#   cd build/release && cpack -G DEB && cd ../.. && tools/check_deb.sh build/release/quad_*_amd64.deb
set -euo pipefail

if [[ $# -lt 1 || ! -f $1 ]]; then
  echo "usage: tools/check_deb.sh PACKAGE.deb [ROOT]" >&2
  exit 2
fi
deb=$(realpath "$1")
root=${2:-$(mktemp -d /tmp/quad-clean-root.XXXXXX)}

# The mirror of this machine's own apt sources (deb822 or one-line form).
mirror=$(sed -n 's/^URIs: *\([^ ]*\).*/\1/p' /etc/apt/sources.list.d/*.sources 2>/dev/null | grep -v security | head -n 1 || true)
if [[ -z $mirror ]]; then
  mirror=$(awk '$1 == "deb" { print $2; exit }' /etc/apt/sources.list 2>/dev/null || true)
fi
if [[ -z $mirror ]]; then
  echo "check_deb: no Debian mirror found in this machine's apt sources" >&2
  exit 1
fi
command -v debootstrap > /dev/null || { apt-get update -qq && apt-get install -y -qq debootstrap; }

cleanup() {
  umount "$root/proc" 2> /dev/null || true
  umount "$root/dev/shm" 2> /dev/null || true
  if [[ ${KEEP_ROOT:-0} != 1 ]]; then rm -rf "$root"; fi
}
trap cleanup EXIT

echo "check_deb: a minimal Debian 12 in $root"
debootstrap --variant=minbase bookworm "$root" "$mirror" > "$root.debootstrap.log" 2>&1 ||
  { tail -n 20 "$root.debootstrap.log" >&2; exit 1; }
rm -f "$root.debootstrap.log"
mount -t proc proc "$root/proc"
mkdir -p "$root/dev/shm" && mount -t tmpfs tmpfs "$root/dev/shm"
cp /etc/resolv.conf "$root/etc/resolv.conf"
cp "$deb" "$root/tmp/quad.deb"

echo "check_deb: apt-get install $(basename "$deb") and what it depends on"
chroot "$root" apt-get update -qq
chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends /tmp/quad.deb > /dev/null

echo "check_deb: quad from /usr, in a folder of its own"
chroot "$root" sh -ec '
  mkdir -p /tmp/elsewhere && cd /tmp/elsewhere
  quad --version
  quad launch demo --check
  quad launch demo --domain 77 --quiet --wall-timeout 300 --log-dir /tmp/elsewhere/run
  grep -q "\"end\": \"success\"" /tmp/elsewhere/run/summary.json
  grep -q "\"collisions\": 0" /tmp/elsewhere/run/summary.json
'
echo "check_deb: PASS: installed on a clean Debian 12 and flew the demo"
