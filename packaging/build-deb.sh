#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds the Debian package artcam-studio_<version>-<release>_<arch>.deb: the project without its
# tests in build-deb/ (RelWithDebInfo, the default of build.sh, so ccache reuses its objects; cpack
# strips the binaries), then `cpack -G DEB`, which installs the two programs with
# the desktop entry, icons, AppStream metainfo, MIME types, manual pages, shell completions, the
# copyright file, the changelog and the sample under /usr and derives Depends with dpkg-shlibdeps
# (cmake/Packaging.cmake). Check the result with lintian (packaging/README.md).
# Usage: bash packaging/build-deb.sh            then: sudo apt-get install ./build-deb/artcam-studio_*.deb
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ARTCAM_DEB_BUILD_DIR:-$root/build-deb}"
bash "$root/packaging/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="${ARTCAM_BUILD_TYPE:-RelWithDebInfo}" \
  -DARTCAM_BUILD_TESTS=OFF "$@"
cmake --build "$build" -j"$(nproc)"
cd "$build"
rm -f artcam-studio_*.deb
cpack -G DEB
deb="$(ls "$build"/artcam-studio_*.deb)"
dpkg-deb --info "$deb"
echo "build-deb: $deb ($(du -h "$deb" | cut -f1))"
