#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Command (b) of the README: install dependencies, build everything, run every test, then the
# sanitizer and fuzzing jobs. Each stage prints how long it took ("stage: NAME took N s").
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ARTCAM_BUILD_DIR:-$root/build}"
source "$root/packaging/stage-timer.sh"
stage "install dependencies" bash "$root/packaging/install-deps.sh"
stage "build" bash "$root/packaging/build.sh"
stage "tests" env -C "$build" QT_QPA_PLATFORM=offscreen ctest --output-on-failure -j"$(nproc)"
# Then the instrumented jobs: ASan+UBSan, the fuzzers, TSan (packaging/ci-sanitizers.sh says
# what each builds and runs). ARTCAM_CI_SANITIZERS=0 skips them; a list ("fuzz tsan") picks some.
case "${ARTCAM_CI_SANITIZERS:-1}" in
  0) ;;
  1) stage "sanitizer jobs" bash "$root/packaging/ci-sanitizers.sh" ;;
  *) read -r -a sanitizer_jobs <<<"$ARTCAM_CI_SANITIZERS"
     stage "sanitizer jobs" bash "$root/packaging/ci-sanitizers.sh" "${sanitizer_jobs[@]}" ;;
esac
stage_summary
