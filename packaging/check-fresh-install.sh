#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs a built .deb on a fresh Debian 12 (a debootstrap minbase chroot, removed afterwards)
# and runs both programs there: shows that the package's Depends pull everything it needs.
# Needs root, debootstrap and the network to a Debian mirror; takes a few minutes and ~1.2 GB
# of /tmp while it runs. Usage: sudo bash packaging/check-fresh-install.sh build-deb/artcam-studio_*.deb
set -euo pipefail
deb="$(realpath "${1:?usage: check-fresh-install.sh PACKAGE.deb}")"
mirror="${DEBIAN_MIRROR:-http://deb.debian.org/debian}"
command -v debootstrap >/dev/null || apt-get install -y -qq --no-install-recommends debootstrap
root="$(mktemp -d /tmp/artcam-fresh-XXXXXX)"
chmod 755 "$root"  # apt's _apt user downloads into it
cleanup() { umount "$root/proc" 2>/dev/null || true; rm -rf --one-file-system "$root"; }
trap cleanup EXIT
debootstrap --variant=minbase bookworm "$root" "$mirror" >/dev/null
printf 'deb %s bookworm-updates main\ndeb %s-security bookworm-security main\n' "$mirror" "$mirror" \
  >>"$root/etc/apt/sources.list"
cp /etc/resolv.conf "$root/etc/resolv.conf"
mount -t proc proc "$root/proc"
cp "$deb" "$root/tmp/"
chroot "$root" /bin/bash -euo pipefail -c '
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y /tmp/'"$(basename "$deb")"' 2>&1 | grep -E "newly installed|^Need to get|^After this"
  examples=/usr/share/artcam-studio/examples
  artcam --version
  artcam warp "$examples/coffee.png" "$examples/sample.artcam" -o /tmp/coffee-warped.png
  artcam-studio --version
  python3 -c "import artcam; print(artcam.read(\"$examples/sample.artcam\"))"
  # The studio opens the sample project and runs until the timeout ends it (status 124).
  status=0; QT_QPA_PLATFORM=offscreen timeout 5 artcam-studio "$examples/sample.artcamproj" \
    >/dev/null 2>&1 || status=$?
  [[ $status -eq 124 ]] || { echo "artcam-studio exited with $status" >&2; exit 1; }
  grep -q "application/x-artcam+json:\*\.artcam$" /usr/share/mime/globs2
  echo "fresh Debian $(cat /etc/debian_version): installed and ran artcam and artcam-studio"'
