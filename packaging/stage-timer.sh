# SPDX-License-Identifier: Apache-2.0
# Sourced by the CI scripts: `stage NAME COMMAND...` runs the command and prints how long it took,
# and `stage_summary` lists every stage's time (CI's log ends with it).
_artcam_stages=()
stage() {
  local name="$1" start status=0
  shift
  start=$(date +%s)
  "$@" || status=$?
  local took=$(($(date +%s) - start))
  _artcam_stages+=("$(printf '%5d s  %s' "$took" "$name")")
  echo "stage: $name took $took s"
  return "$status"
}
stage_summary() {
  echo "stage times:"
  printf '  %s\n' "${_artcam_stages[@]}"
}
