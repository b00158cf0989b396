#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# CI's instrumented jobs, run by packaging/build-and-test.sh after the normal build and tests:
#
#   asan  GCC, ASan + UBSan, -O1: instruments the layers untrusted input passes through (the
#         readers in core/io, core/model, core/project and core/lens, the renderers and
#         their layers in core/mapping, core/sampling, core/render, core/piecewise and
#         core/pipeline, core/util, and the CLI in app/); runs
#         the readers' tests (core/io, core/model/artcam and coverage) and app/hostile_warp with
#         leak checking, and the hostile corpus (tests/hostile) through the instrumented artcam.
#         Any report fails the job.
#   fuzz  clang 14, libFuzzer + ASan + UBSan: every reader's fuzzer for ARTCAM_CI_FUZZ_SECONDS
#         (default 5) from its checked-in corpus. What a fuzzer finds is left in
#         build-fuzz/fuzz/findings/ and listed; it becomes a regression seed by being copied to
#         fuzz/corpus/<target>/found-<what>, which the normal build replays on every test run.
#   tsan  GCC, TSan, -O1: instruments ui/, tests/ui and core/util (the engine's thread pool);
#         runs ui/preview, 1 000 rapid edits through the newest-request worker (the preview's
#         render and fit workers), with cmake/tsan.supp for uninstrumented Qt. Not
#         ui/background_job: the one-shot jobs run on QThreadPool, whose threads race inside
#         libQt6Core (memmove between two pooled threads, no frame of ours) in a way no
#         suppression can single out without hiding our own races; it needs a TSan-built Qt.
#
# What each tree instruments, and why not everything: CI has two cores and 90 minutes, and
# .ci/run must fit well inside 40 from a cold cache (each stage prints its time). cmake/Sanitizers.cmake
# puts the sanitizer flags on the chosen sources only
# (ARTCAM_SANITIZE_ONLY), so every other source compiles with the normal build's exact command
# line and ccache returns the object the normal build made minutes before (the root
# CMakeLists.txt keeps the build directory out of ccache's key): a tree costs what it instruments. Left uninstrumented under ASan: the numerical layers (core/fit, core/effects,
# core/colour, core/cameras, core/depth, core/cloud), which see only values a reader has
# already checked, and the test programs themselves. ARTCAM_CI_ASAN_ONLY / ARTCAM_CI_TSAN_ONLY
# change the lists ("core;app;ui;tests" is everything). The fuzz job leaves out fuzz_project,
# whose target links the whole engine a second time (ARTCAM_CI_FUZZ_PROJECT=1 adds it); the
# corpus replay covers the project reader instead.
#
# usage: ci-sanitizers.sh [asan] [fuzz] [tsan]   (default: all three)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${ARTCAM_CI_JOBS:-$(nproc)}"
selected=("$@")
[[ ${#selected[@]} -eq 0 ]] && selected=(asan fuzz tsan)
# The normal build's type, so uninstrumented sources hit ccache; -O1 only where instrumented.
flags_o1=(-DCMAKE_BUILD_TYPE="${ARTCAM_BUILD_TYPE:-RelWithDebInfo}" "-DARTCAM_SANITIZE_FLAGS=-O1 -g1")
asan_only="${ARTCAM_CI_ASAN_ONLY:-core/io;core/model;core/project;core/lens;core/mapping;core/sampling;core/render;core/piecewise;core/pipeline;core/util;app}"
tsan_only="${ARTCAM_CI_TSAN_ONLY:-ui;tests/ui;core/util}"

source "$root/packaging/stage-timer.sh"

asan() {
  local build="${ARTCAM_ASAN_DIR:-$root/build-asan}"
  stage "asan configure" cmake -S "$root" -B "$build" -G Ninja "${flags_o1[@]}" \
    -DARTCAM_SANITIZE=address,undefined -DARTCAM_SANITIZE_ONLY="$asan_only" \
    -DARTCAM_BUILD_GUI=OFF >/dev/null
  local targets=(artcam test_app_hostile_warp)
  targets+=($(ninja -C "$build" -t targets all | grep -oE '^test_core_io_[a-z0-9_]+' | sort -u))
  targets+=(test_core_model_artcam test_core_model_coverage)
  stage "asan build (${#targets[@]} targets)" cmake --build "$build" -j"$jobs" --target "${targets[@]}"
  # The tests with leak checking: LSan's suppression (cmake/lsan.supp, a leak inside OIIO's PNG
  # reader) needs the slow unwinder on every malloc.
  stage "asan tests" env -C "$build" \
    ASAN_OPTIONS="fast_unwind_on_malloc=0:detect_leaks=1:exitcode=86" \
    LSAN_OPTIONS="suppressions=$root/cmake/lsan.supp:print_suppressions=0" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=87" \
    QT_QPA_PLATFORM=offscreen \
    ctest --output-on-failure --no-tests=error -j"$jobs" -R '^(core/io/.*|core/model/(artcam|coverage)|app/hostile_warp)$'
  # The hostile corpus (about 300 runs of artcam) without leak checking, which would triple its
  # time: memory errors and undefined behaviour are still fatal; the readers' leaks are the tests'
  # above, which read the same kinds of files.
  stage "asan hostile corpus" env -C "$build" \
    ASAN_OPTIONS="detect_leaks=0:exitcode=86" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=87" \
    ARTCAM_HOSTILE_SANITIZED=1 ARTCAM_HOSTILE_JOBS="$jobs" QT_QPA_PLATFORM=offscreen \
    ctest --output-on-failure --no-tests=error -R '^hostile/corpus$'
}

fuzz() {
  local build="${ARTCAM_FUZZ_DIR:-$root/build-fuzz}"
  local cxx="${ARTCAM_FUZZ_CXX:-clang++-14}"
  local names=(artcam piecewise matches_csv colour_csv walls_csv ply)
  [[ "${ARTCAM_CI_FUZZ_PROJECT:-0}" == 1 ]] && names+=(project)
  CXX="$cxx" stage "fuzz configure" cmake -S "$root" -B "$build" -G Ninja \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DARTCAM_FUZZ=ON -DARTCAM_BUILD_GUI=OFF \
    -DARTCAM_BUILD_TESTS=OFF -DARTCAM_FUZZ_SECONDS="${ARTCAM_CI_FUZZ_SECONDS:-5}" >/dev/null
  stage "fuzz build (${#names[@]} fuzzers)" cmake --build "$build" -j"$jobs" \
    --target "${names[@]/#/fuzz_}"
  local pattern
  pattern="^fuzz/($(IFS='|'; echo "${names[*]}"))$"
  local status=0
  # The fuzz tests live in build-fuzz/fuzz (the root enables no tests without ARTCAM_BUILD_TESTS).
  stage "fuzz runs" env -C "$build/fuzz" ctest --output-on-failure --no-tests=error -R "$pattern" ||
    status=$?
  if compgen -G "$build/fuzz/findings/*" >/dev/null; then
    echo "ci-sanitizers: the fuzzers found inputs to keep as regression seeds" \
      "(fuzz/corpus/<target>/found-<what>):"
    ls -l "$build"/fuzz/findings/
  fi
  return "$status"
}

tsan() {
  local build="${ARTCAM_TSAN_DIR:-$root/build-tsan}"
  stage "tsan configure" cmake -S "$root" -B "$build" -G Ninja "${flags_o1[@]}" \
    -DARTCAM_SANITIZE=thread -DARTCAM_SANITIZE_ONLY="$tsan_only" >/dev/null
  stage "tsan build" cmake --build "$build" -j"$jobs" --target test_ui_preview test_core_util_parallel
  # setarch -R: TSan's shadow layout does not fit high-entropy ASLR (Debian 12's kernels).
  stage "tsan tests" env -C "$build" \
    TSAN_OPTIONS="suppressions=$root/cmake/tsan.supp:halt_on_error=1:exitcode=66" \
    QT_QPA_PLATFORM=offscreen \
    setarch "$(uname -m)" -R ctest --output-on-failure --no-tests=error \
      -R '^(ui/preview|core/util/parallel)$'
}

for job in "${selected[@]}"; do
  case "$job" in
    asan | fuzz | tsan) "$job" ;;
    *) echo "ci-sanitizers: unknown job $job (asan, fuzz, tsan)" >&2; exit 2 ;;
  esac
done
stage_summary
