#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Command (b) of the README: install dependencies, build everything, run every test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ARTCAM_BUILD_DIR:-$root/build}"
bash "$root/packaging/install-deps.sh"
bash "$root/packaging/build.sh"
cd "$build"
QT_QPA_PLATFORM=offscreen ctest --output-on-failure -j"$(nproc)"
