#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Long fuzzing runs (README, "Hostile input, fuzzing and sanitizers").
#   fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET…]     (default: every target)
# Needs a build configured with ARTCAM_FUZZ=ON (clang). Each target fuzzes for SECONDS from the
# checked-in corpus fuzz/corpus/<target>/ (only read) into BUILD_DIR/fuzz/work/<target>/ (the
# coverage corpus grows there between runs and is not checked in). Crashes, timeouts and
# out-of-memory inputs land in BUILD_DIR/fuzz/findings/<target>/; once the reader is fixed,
# check each one in, minimised, as fuzz/corpus/<target>/found-*, so the replay test
# (tests/core/io/test_hostile_inputs.cpp) keeps it fixed. Runs at nice 10: the machine is shared.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:?usage: run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]}"
seconds="${2:?usage: run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]}"
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(artcam piecewise matches_csv colour_csv ply project)
for t in "${targets[@]}"; do
  exe="$build/fuzz/fuzz_$t"
  work="$build/fuzz/work/$t"
  findings="$build/fuzz/findings/$t"
  mkdir -p "$work" "$findings"
  limits=(-rss_limit_mb=2048 -malloc_limit_mb=512)
  [ "$t" = project ] && limits=(-rss_limit_mb=3072 -malloc_limit_mb=1100)
  echo "== $t: ${seconds}s"
  nice -n 10 "$exe" -max_total_time="$seconds" "${limits[@]}" -timeout=5 -max_len=16384 \
    -print_final_stats=1 -artifact_prefix="$findings/" "$work" "$root/fuzz/corpus/$t" 2>&1 |
    grep -E '^(#[0-9]+ +DONE|stat::|==[0-9]+==ERROR|SUMMARY|Test unit written|bad refusal|fuzz check)' || true
  ls "$findings"
done
