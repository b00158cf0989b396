#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Configures ARTcam Studio into build/ with Ninja (and ccache when installed) and builds it:
# everything (CLI, studio, tests), or only ARTCAM_BUILD_TARGETS (e.g. "artcam artcam-studio",
# what packaging/run-demo.sh needs). Arguments are passed to cmake's configure step.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ARTCAM_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="${ARTCAM_BUILD_TYPE:-RelWithDebInfo}" "$@"
targets=()
if [[ -n "${ARTCAM_BUILD_TARGETS:-}" ]]; then
  read -r -a targets <<<"$ARTCAM_BUILD_TARGETS"
  targets=(--target "${targets[@]}")
fi
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
