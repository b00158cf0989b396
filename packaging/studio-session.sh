#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A scripted session in the REAL artcam-studio window under Xvfb, driven by xdotool the way a
# user drives it: mouse clicks and drags at photo or result points, keyboard shortcuts, menus by
# their mnemonics, file dialogs by typing a path. It leaves numbered screenshots and a log of
# every step in OUTDIR, and fails (exit 1, naming the checks) when any check below fails.
#
# Usage: bash packaging/studio-session.sh [OUTDIR]      (default: build/studio-session)
# Environment: STUDIO, ARTCAM (the binaries; default build/app/...), DISPLAY_NUMBER (default: the
# first free of :90...:99), STEP_WAIT (seconds a render gets before a shot, default 2).
# Needs the Debian packages xvfb, xdotool and imagemagick (install-deps.sh --with-display), and
# /usr/bin/python3 with numpy (packaging/studio_session_check.py: the grid and the measures).
#
# The session, with the check each step gets:
#  1. open a copy of resources/coffee.png;
#  2. place nine source->target pairs of a bulge on the Result view, each source clicked where
#     the result shows the photo point meant, then drag one target and one source there: the
#     saved pairs are the points meant (the sources mapped back through the camera's inverse);
#  3. open a barrel-distorted grid (made in code: 90 px squares through a division lens), trace
#     two horizontal and two vertical lines with the Line tool, export the image and the camera:
#     the grid lines are 90 px apart within 3 %, the studio's camera maps as `artcam fit
#     --lines` of the saved lines does, and `artcam warp` with that camera is the export;
#  4. reopen the coffee project, add aerial perspective and depth of field, paint two depth
#     planes (polygons and depth points) on the Result view while depth of field shows: the
#     depth points lie where the result showed them;
#  5. export; start a second studio while this one runs with unsaved work: it offers no
#     recovery; save and quit;
#  6. move the photo, reopen the project, answer its Locate… prompt with the new place, export
#     again: identical to the first export and to `artcam export --photo`;
#  7. a control for 5: a studio killed with unsaved work is offered to the next one.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
outdir="${1:-$root/build/studio-session}"
studio_bin="${STUDIO:-$root/build/app/artcam-studio}"
artcam_bin="${ARTCAM:-$root/build/app/artcam}"
step_wait="${STEP_WAIT:-2}"
photo_src="$root/resources/coffee.png"

for tool in Xvfb xdotool import convert compare identify; do
  command -v "$tool" >/dev/null || {
    echo "studio-session: $tool is missing (bash packaging/install-deps.sh --with-display)" >&2
    exit 1
  }
done
[[ -x "$studio_bin" && -x "$artcam_bin" ]] || {
  echo "studio-session: build artcam and artcam-studio first ($studio_bin, $artcam_bin)" >&2
  exit 1
}

# Everything the session writes stays in OUTDIR: the photo's copy, the project and the exports
# sit in OUTDIR/files so they can be inspected afterwards; the studio's settings, recent files
# and autosave recovery go to a throw-away XDG home, so no earlier session (and no recovery
# prompt) leaks into this one and this one leaves nothing in the user's home.
mkdir -p "$outdir"
outdir="$(cd "$outdir" && pwd)"
files="$outdir/files"
rm -rf "$files"
rm -f "$outdir"/[0-9][0-9]-*.png "$outdir/session.log"
mkdir -p "$files"
cp "$photo_src" "$files/coffee.png"
home="$(mktemp -d)"
log="$outdir/session.log"
# The barrel grid and the points on it a user clicks to trace its lines, made in code; its
# truth (the spacing) is the generator's constant, outside the code under test.
grid_spacing=90
/usr/bin/python3 "$root/packaging/studio_session_check.py" grid "$home/grid.ppm" \
  "$files/grid-clicks.txt" >/dev/null
convert "$home/grid.ppm" "$files/grid.png"
photo_w=0 photo_h=0

# The screen is larger than the window so the mouse can be parked off the window (no hover
# highlights or tooltips in the shots); with no window manager the window sits at 0,0 undecorated.
screen_w=1600 screen_h=1000 win_w=1400 win_h=900
display="${DISPLAY_NUMBER:-}"
if [[ -z "$display" ]]; then
  for n in $(seq 90 99); do
    if [[ ! -e "/tmp/.X$n-lock" && ! -e "/tmp/.X11-unix/X$n" ]]; then display=":$n"; break; fi
  done
fi
[[ -n "$display" ]] || { echo "studio-session: no free X display in :90...:99" >&2; exit 1; }
export DISPLAY="$display"
export XDG_CONFIG_HOME="$home/config" XDG_DATA_HOME="$home/data" XDG_CACHE_HOME="$home/cache"
export XDG_RUNTIME_DIR="$home/runtime"
# The autosave every 1.5 s, so the second-instance check meets a live recovery file.
export ARTCAM_AUTOSAVE_INTERVAL_MS=1500
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
# Qt's own file dialog (typed paths), whatever desktop theme the caller's environment names.
unset QT_QPA_PLATFORMTHEME
export QT_QPA_PLATFORM=xcb

xvfb_pid=""
studio_pid=""
cleanup() {
  if [[ -n "$studio_pid" ]]; then kill "$studio_pid" 2>/dev/null || true; fi
  if [[ -n "$xvfb_pid" ]]; then kill "$xvfb_pid" 2>/dev/null || true; fi
  wait 2>/dev/null || true
  rm -rf "$home"
}
trap cleanup EXIT

step_n=0
shot_n=0
notes=0
log() { printf '%s %s\n' "$(date -u +%H:%M:%S)" "$*" | tee -a "$log"; }
step() {
  step_n=$((step_n + 1))
  log "step $step_n: $*"
}
note() {  # something that could not be driven or checked as meant; the session goes on
  notes=$((notes + 1))
  log "  NOTE: $*"
}
park_mouse() { xdotool mousemove $((screen_w - 10)) $((screen_h - 10)); }
shot() {  # shot NAME WHAT: a numbered screenshot of the whole screen, cropped to the window
  shot_n=$((shot_n + 1))
  local f
  f="$outdir/$(printf '%02d' "$shot_n")-$1.png"
  park_mouse
  sleep "$step_wait"
  import -window root "$f.full.png"
  convert "$f.full.png" -crop "${win_w}x${win_h}+0+0" +repage -strip "$f"
  rm -f "$f.full.png"
  log "  shot $(basename "$f"): $2"
}

# --- the window -------------------------------------------------------------------------------

main_win=""
find_main_window() {  # the studio's visible top-level window (its title ends in "ARTcam Studio")
  local w g
  for _ in $(seq 1 100); do
    for w in $(xdotool search --onlyvisible --name 'ARTcam Studio$' 2>/dev/null || true); do
      g="$(xdotool getwindowgeometry "$w" | awk '/Geometry:/ {print $2}')"
      if [[ "${g%x*}" -ge 400 ]]; then
        main_win="$w"
        return 0
      fi
    done
    sleep 0.2
  done
  return 1
}
focus_main() { xdotool windowfocus --sync "$main_win"; }
key() {  # key KEYSYM...: keys to the main window (it has the X input focus; no window manager)
  focus_main
  xdotool key --delay 80 "$@"
  sleep 0.3
}
menu() {  # menu MENU_MNEMONIC ITEM_MNEMONIC: a menu entry by keyboard, as Alt+T, Y
  key "alt+$1"
  sleep 0.3
  xdotool key "$2"
  sleep 0.3
}

start_studio() {  # start_studio FILE [nowait]: the studio on FILE, window placed and sized,
  # loaded (nowait: not waiting for the title to name FILE, as when a prompt comes first)
  "$studio_bin" "$1" >>"$outdir/files/studio-stderr.log" 2>&1 &
  studio_pid=$!
  find_main_window || { log "the studio window did not appear"; exit 1; }
  xdotool windowmove --sync "$main_win" 0 0 || true
  xdotool windowsize --sync "$main_win" "$win_w" "$win_h" || true
  local g
  g="$(xdotool getwindowgeometry "$main_win" | tr '\n' ' ' | sed 's/  */ /g')"
  log "  window $main_win: $g"
  # The photo loads in a worker; the title names the file once it is in.
  [[ "${2:-}" == nowait ]] && return 0
  for _ in $(seq 1 50); do
    if xdotool getwindowname "$main_win" | grep -q "$(basename "$1")"; then break; fi
    sleep 0.2
  done
  sleep 1
}

wait_exit() {  # wait_exit SECONDS: true when the studio process ended in time
  local i
  for i in $(seq 1 $(($1 * 5))); do
    if ! kill -0 "$studio_pid" 2>/dev/null; then
      wait "$studio_pid" 2>/dev/null || true
      studio_pid=""
      return 0
    fi
    sleep 0.2
  done
  return 1
}

wait_window() {  # wait_window TITLE_REGEX SECONDS: the id of the visible window so named
  local w
  for _ in $(seq 1 $(($2 * 5))); do
    w="$(xdotool search --onlyvisible --name "$1" 2>/dev/null | head -n 1 || true)"
    if [[ -n "$w" ]]; then
      echo "$w"
      return 0
    fi
    sleep 0.2
  done
  return 1
}

wait_file() {  # wait_file PATH SECONDS: the studio writes beside and renames into place
  for _ in $(seq 1 $(($2 * 5))); do
    [[ -s "$1" ]] && return 0
    sleep 0.2
  done
  return 1
}

# file_dialog TITLE PATH: type PATH into the Qt file dialog titled TITLE and accept it. The name
# field has the focus and holds the suggestion; Ctrl+A replaces it. Returns 1 when no dialog came.
file_dialog() {
  local w
  w="$(wait_window "^$1\$" 10)" || return 1
  xdotool windowfocus --sync "$w"
  sleep 0.5
  xdotool key ctrl+a
  xdotool type --delay 20 "$2"
  sleep 0.5
  xdotool key Return
  sleep 0.5
}

# export_image PATH: File > Export Warped Image (Ctrl+E), the path typed into its file dialog,
# then the export options dialog accepted as it opens (Return: keep transparent pixels, the
# photo's bit depth; what artcam export does by default), then the file awaited.
export_image() {
  local w
  key ctrl+e
  file_dialog "Export warped image" "$1" || { note "no export file dialog"; return 1; }
  if w="$(wait_window '^Export options$' 10)"; then
    xdotool windowfocus --sync "$w"
    sleep 0.3
    xdotool key Return
  else
    log "  (no export options dialog: this build exports at once)"
  fi
  wait_file "$1" 60 || { note "the export did not write $(basename "$1")"; return 1; }
  log "  exported $(basename "$1"): $(identify -format '%wx%h %[channels] %[bit-depth]-bit' "$1")"
}

# --- photo pixels -> screen pixels --------------------------------------------------------------
# The canvas fits the photo into itself with an 8 px margin, centred (ViewTransform::fit), until
# the user zooms. The canvas's rectangle is found on a screenshot: the longest run of its
# background colour (48, 48, 52) down a column at its left margin, then along a row in its top
# margin. That survives changes to the toolbars and docks around it, which fixed numbers would not.
canvas_bg="#303034"
longest_run() {  # stdin: ImageMagick txt: pixels of one line; prints "first last" of the run
  awk -v bg="$canvas_bg" -v axis="$1" '
    NR > 1 {
      split($1, c, /[,:]/); p = (axis == "x") ? c[1] : c[2]
      if ($3 != bg) { start = -1; next }
      if (start < 0) start = p
      if (p - start > best) { best = p - start; a = start; b = p }
    }
    BEGIN { start = -1; best = -1 }
    END { print a, b }'
}
calibrate() {  # calibrate [quiet]: quiet logs only a change
  park_mouse
  sleep 0.5
  import -window root "$home/cal.png"
  local top bottom left right cw ch
  read -r top bottom < <(convert "$home/cal.png" -crop "1x${win_h}+2+0" +repage txt:- |
    longest_run y)
  read -r left right < <(convert "$home/cal.png" -crop "${win_w}x1+0+$((top + 2))" +repage txt:- |
    longest_run x)
  cw=$((right - left + 1))
  ch=$((bottom - top + 1))
  read -r scale off_x off_y < <(awk -v cw="$cw" -v ch="$ch" -v w="$photo_w" -v h="$photo_h" \
    -v l="$left" -v t="$top" 'BEGIN {
      sx = (cw - 16) / w; sy = (ch - 16) / h; s = sx < sy ? sx : sy
      printf "%.9f %.9f %.9f\n", s, l + (cw - w * s) / 2, t + (ch - h * s) / 2 }')
  local now="canvas at ${left},${top} size ${cw}x${ch}: photo pixel (x, y) is screen"
  now+=" (${off_x} + ${scale} x, ${off_y} + ${scale} y)"
  if [[ "${1:-}" != quiet || "$now" != "$calibration" ]]; then log "  $now"; fi
  calibration="$now"
}
calibration=""
screen_of() {  # screen_of X Y (photo pixels) -> "SX SY" (the nearest screen pixel)
  awk -v x="$1" -v y="$2" -v s="$scale" -v ox="$off_x" -v oy="$off_y" \
    'BEGIN { printf "%d %d\n", ox + x * s + 0.5, oy + y * s + 0.5 }'
}
click_photo() {  # click_photo X Y: a left click at photo pixel (X, Y)
  local sx sy
  read -r sx sy < <(screen_of "$1" "$2")
  xdotool mousemove "$sx" "$sy"
  sleep 0.15
  xdotool click 1
  sleep 0.25
}
click_screen() {  # click_screen X Y: a left click at window pixel (X, Y) (docks' controls)
  xdotool mousemove "$1" "$2"
  sleep 0.15
  xdotool click 1
  sleep 0.3
}

# What has no shortcut is clicked at its place in the 1400x900 window: the dock tabs along its
# bottom edge and the Effects panel's list of effects, its first row. Measured on this window;
# the shots show where the clicks landed and the project check at the end catches a miss. The
# Depth panel's Next depth field (Alt+N) and the Effects panel's Add button (Alt+A) have
# mnemonics, so the rows added to those panels over time move no click.
depth_tab=(1120 863)
effects_tab=(1184 863)
effect_combo=(1112 86)

set_next_depth() {  # the Depth panel's "Next depth" spin box: the depth of the next clicked point
  key alt+n
  xdotool key ctrl+a
  xdotool type --delay 30 "$1"
  xdotool key Tab
  sleep 0.3
}

# --- the session's own truths: cameras made by artcam from the intended clicks ------------------

calc() { awk "BEGIN { printf \"%.2f\", $1 }"; }
use_photo() {  # use_photo FILE: the photo the canvas shows from now on (its size for calibrate)
  read -r photo_w photo_h < <(identify -format '%w %h\n' "$1")
}

# camera_of PAIRS OUT.artcam: the camera the studio makes of PAIRS (one "sx sy tx ty" a line) on
# the photo: a project of them, rendered by `artcam export --camera-out` (the project's fit is
# the studio document's, core/project/document_camera.h).
camera_of() {
  printf '%s' "$1" >"$home/pairs-now.txt"
  /usr/bin/python3 "$check" project "$files/coffee.png" "$home/pairs-now.txt" "$home/pairs-now.artcamproj"
  "$artcam_bin" export "$home/pairs-now.artcamproj" -o "$home/pairs-now.png" --camera-out "$2" \
    --quiet --overwrite >/dev/null 2>"$home/fit.err"
}
map_point() {  # map_point CAM X Y: "X' Y'", the camera's image of pixel (X, Y)
  printf 'x,y\n%s,%s\n' "$2" "$3" >"$home/point.csv"
  "$artcam_bin" map "$1" "$home/point.csv" | tail -n 1 | awk -F, '{ printf "%.2f %.2f\n", $3, $4 }'
}
# result_of PAIRS X Y: where the result shows photo pixel (X, Y) while the studio holds PAIRS;
# the photo pixel itself while there are none.
result_of() {
  if [[ -z "${1//[[:space:]]/}" ]]; then
    printf '%s %s\n' "$2" "$3"
    return
  fi
  if ! camera_of "$1" "$home/fit.artcam"; then
    note "the camera of the pairs so far could not be made: $(head -n 1 "$home/fit.err")"
    printf '%s %s\n' "$2" "$3"
    return
  fi
  map_point "$home/fit.artcam" "$2" "$3"
}

drag_photo() {  # drag_photo X0 Y0 X1 Y1: a left-button drag between two photo/result pixels
  local ax ay bx by i
  read -r ax ay < <(screen_of "$1" "$2")
  read -r bx by < <(screen_of "$3" "$4")
  xdotool mousemove "$ax" "$ay"
  sleep 0.2
  xdotool mousedown 1
  sleep 0.2
  for i in 1 2 3 4 5 6 7 8; do
    xdotool mousemove $((ax + (bx - ax) * i / 8)) $((ay + (by - ay) * i / 8))
    sleep 0.08
  done
  sleep 0.2
  xdotool mouseup 1
  sleep 0.5
}

wait_title() {  # wait_title NAME SECONDS: the main window's title names NAME
  for _ in $(seq 1 $(($2 * 5))); do
    if xdotool getwindowname "$main_win" 2>/dev/null | grep -qF "$1"; then
      sleep 1
      return 0
    fi
    sleep 0.2
  done
  return 1
}

save_project() {  # save_project PATH: Ctrl+S, through Save As's dialog when it comes
  local before=""
  [[ -e "$1" ]] && before="$(stat -c %Y.%s "$1")"
  rm -f "$1.saved"
  key ctrl+s
  if w="$(wait_window '^Save project$' 4)"; then
    file_dialog "Save project" "$1" || true
  fi
  for _ in $(seq 1 100); do
    if [[ -s "$1" && "$(stat -c %Y.%s "$1")" != "$before" ]]; then
      sleep 0.5
      log "  saved $(basename "$1"): $(wc -c <"$1") bytes"
      return 0
    fi
    sleep 0.2
  done
  # The same second and size as before is a save too; the title's modified mark says which.
  if xdotool getwindowname "$main_win" | grep -qF '*'; then
    note "the project $(basename "$1") was not saved"
    return 1
  fi
  log "  saved $(basename "$1") (unchanged size and time)"
}

quit_studio() {  # Ctrl+Q; an unsaved-changes prompt is answered Discard
  key ctrl+q
  if ! wait_exit 10; then
    if w="$(wait_window '^Unsaved changes$' 1)"; then
      note "the studio asked to save unsaved changes on quit; answered Discard"
      xdotool windowfocus --sync "$w"
      xdotool key alt+d
    fi
    if ! wait_exit 10; then
      note "the studio did not quit; killed"
      kill "$studio_pid"
      wait_exit 5 || true
    fi
  fi
}

compare_pair() {  # compare_pair A B: logs the number of differing pixels; fails when any
  if [[ ! -s "$1" || ! -s "$2" ]]; then
    fail "$(basename "$1") vs $(basename "$2")" "missing"
    return
  fi
  local ae status=0
  ae="$(compare -metric AE "$1" "$2" null: 2>&1)" || status=$?
  log "  $(basename "$1") vs $(basename "$2"): $ae pixels differ"
  if [[ "$status" -ne 0 ]]; then fail "$(basename "$1") vs $(basename "$2")" "$ae pixels differ"; fi
}

check="$root/packaging/studio_session_check.py"

# snapshot_before N: the studio's pairs as its autosave holds them before pair N's clicks (the
# autosave runs every ARTCAM_AUTOSAVE_INTERVAL_MS while the document is modified), so the check
# can rebuild the very camera each source click was mapped back through.
snapshot_before() {
  local r="" i
  if [[ "$1" -gt 1 ]]; then
    for i in $(seq 1 40); do
      r="$(recovery_files | head -n 1)"
      if [[ -n "$r" ]] && /usr/bin/python3 -c 'import json, sys
sys.exit(len(json.load(open(sys.argv[1])).get("pairs", [])) != int(sys.argv[2]))' "$r" "$(($1 - 1))" 2>/dev/null; then
        cp "$r" "$home/snapshot-$1.artcamproj"
        return 0
      fi
      sleep 0.2
    done
    note "no autosave with $(($1 - 1)) pairs before pair $1"
  fi
}

# The saved pairs are what the clicks and drags on the result meant: each source the photo
# point the click on the result showed (mapped back through the studio's camera), pair 5's
# target where it was dropped, pair 9's source where the drag through the inverse put it: the
# nine pairs of the bulge. Tolerance 1.5 px: a screen pixel's rounding (0.7 photo px) through
# the camera, and earlier sources' rounding in the camera of the next click.
check_pairs() {
  local status=0 n rx ry x y X Y
  /usr/bin/python3 - "$project" "$placed" >"$home/pairs.txt" 2>&1 <<'PY' || status=$?
import json, sys
pairs = json.load(open(sys.argv[1])).get("pairs", [])
want = [[float(v) for v in line.split()] for line in sys.argv[2].split("\n") if line.strip()]
if len(pairs) != len(want):
    print("%d pairs saved, %d placed" % (len(pairs), len(want)))
    sys.exit(1)
worst, where = 0.0, ""
for i, (p, w) in enumerate(zip(pairs, want)):
    for (x, y), (a, b), what in ((p["source"], w[0:2], "source"), (p["target"], w[2:4], "target")):
        d = ((x - a) ** 2 + (y - b) ** 2) ** 0.5
        if d > worst:
            worst, where = d, "pair %d's %s" % (i + 1, what)
print("%d pairs saved; against the bulge's points the worst, %s, is %.2f px off" % (len(pairs), where, worst))
t5 = pairs[4]["target"]
d5 = ((t5[0] - want[4][2]) ** 2 + (t5[1] - want[4][3]) ** 2) ** 0.5
print("pair 5's target after its drag on the result: (%.2f, %.2f), %.2f px from the drop point" % (t5[0], t5[1], d5))
print("pair 9's source after its drag on the result: (%.2f, %.2f), the bulge's (%.2f, %.2f)" % (
    pairs[8]["source"][0], pairs[8]["source"][1], want[8][0], want[8][1]))
if d5 > 1.0:
    sys.exit(1)
PY
  while IFS= read -r line; do log "  $line"; done <"$home/pairs.txt"
  if [[ "$status" -ne 0 ]]; then fail "pair 5's dragged target"; fi
  # Each source click on the result, against the studio's own camera of the pairs before it:
  # that camera maps the saved source back onto the clicked result pixel.
  local worst=0
  for n in 2 3 4 5 6 7 8 9; do
    [[ -s "$home/snapshot-$n.artcamproj" ]] || continue
    "$artcam_bin" export "$home/snapshot-$n.artcamproj" -o "$home/snap.png" \
      --camera-out "$home/snap.artcam" --quiet --overwrite >/dev/null 2>&1 || continue
    read -r rx ry < <(sed -n "${n}p" "$home/source-clicks.txt")
    read -r x y < <(/usr/bin/python3 -c 'import json, sys
p = json.load(open(sys.argv[1]))["pairs"][int(sys.argv[2]) - 1]["source"]; print(p[0], p[1])' \
      "$home/snapshot-10.artcamproj" "$n")
    read -r X Y < <(map_point "$home/snap.artcam" "$x" "$y")
    worst="$(awk -v a="$X" -v b="$Y" -v c="$rx" -v d="$ry" -v w="$worst" 'BEGIN {
      e = sqrt((a - c) ^ 2 + (b - d) ^ 2); printf "%.2f", (e > w ? e : w) }')"
  done
  log "  sources clicked on the result: the studio's camera of the pairs before each maps the" \
    "recorded source to within $worst px of the click"
  if ! awk -v w="$worst" 'BEGIN { exit !(w <= 1.0) }'; then fail "sources through the inverse"; fi
}

# The straightened grid against its truth, and the studio's camera against `artcam fit --lines`
# on the project's lines: both map the same 24x18 points (max difference under 0.01 px), and
# `artcam warp` with the CLI's camera renders the studio's export pixel for pixel.
check_lines() {
  local status=0 model
  if [[ -s "$grid_export" ]]; then
    convert "$grid_export" -alpha off -colorspace gray -depth 8 "$home/grid.pgm"
    convert "$grid_export" -alpha extract -depth 8 "$home/grid-alpha.pgm"
    /usr/bin/python3 "$check" spacing "$home/grid.pgm" "$home/grid-alpha.pgm" >"$home/spacing.txt" 2>&1 ||
      status=$?
    while IFS= read -r line; do log "  $line"; done <"$home/spacing.txt"
    if [[ "$status" -ne 0 ]]; then fail "grid spacing within 3 % of $grid_spacing px"; fi
  else
    fail "grid export" "missing"
  fi
  [[ -s "$grid_project" ]] || { fail "grid project" "missing"; return; }
  model="$(/usr/bin/python3 "$check" lines "$grid_project" "$files/grid-lines.csv" 2>"$home/lines.txt")"
  log "  $(cat "$home/lines.txt"); line model $model"
  status=0
  "$artcam_bin" fit --lines "$files/grid-lines.csv" -o "$files/grid-cli.artcam" \
    --size "${photo_w}x${photo_h}" --model "$model" --quiet --overwrite >"$home/fit-lines.txt" 2>&1 ||
    status=$?
  while IFS= read -r line; do log "  artcam fit --lines: $line"; done < <(head -n 2 "$home/fit-lines.txt")
  if [[ "$status" -ne 0 ]]; then fail "artcam fit --lines" "exit status $status"; return; fi
  awk -v w="$photo_w" -v h="$photo_h" 'BEGIN { print "x,y"
    for (j = 0; j < 18; ++j) for (i = 0; i < 24; ++i)
      printf "%.3f,%.3f\n", (i + 0.5) * w / 24, (j + 0.5) * h / 18 }' >"$home/grid-points.csv"
  if [[ -s "$files/grid-studio.artcam" ]]; then
    "$artcam_bin" map "$files/grid-studio.artcam" "$home/grid-points.csv" >"$home/map-studio.csv"
    "$artcam_bin" map "$files/grid-cli.artcam" "$home/grid-points.csv" >"$home/map-cli.csv"
    status=0
    /usr/bin/python3 "$check" mapdiff "$home/map-studio.csv" "$home/map-cli.csv" \
      >"$home/mapdiff.txt" 2>&1 || status=$?
    log "  studio camera vs artcam fit --lines: $(cat "$home/mapdiff.txt")"
    if [[ "$status" -ne 0 ]]; then fail "studio camera = artcam fit --lines"; fi
  else
    fail "studio camera" "not exported"
  fi
  "$artcam_bin" warp "$files/grid.png" "$files/grid-cli.artcam" -o "$files/grid-cli.png" \
    --quiet --overwrite >/dev/null 2>&1 || fail "artcam warp with the fit --lines camera"
  # artcam warp quantises its float result by another path than the project's export, so the
  # CLI camera's warp may differ by one code value; the project's own export must be identical.
  local pae
  pae="$(compare -metric PAE "$grid_export" "$files/grid-cli.png" null: 2>&1)" || true
  ae="$(compare -metric AE "$grid_export" "$files/grid-cli.png" null: 2>&1)" || true
  log "  grid-export.png vs artcam warp with the fit --lines camera: $ae pixels differ, by at" \
    "most $pae"
  if ! awk -v p="${pae#*(}" 'BEGIN { exit !(p + 0 <= 1.5 / 255) }'; then
    fail "grid export vs artcam warp" "differs by $pae"
  fi
  "$artcam_bin" export "$grid_project" -o "$files/grid-cli-export.png" --quiet --overwrite \
    >/dev/null 2>&1 || fail "artcam export of the grid project"
  compare_pair "$grid_export" "$files/grid-cli-export.png"
}

# The saved coffee project holds nine pairs, the two planes with the typed depths and the two
# effects (a missed click shows up here).
check_project() {
  local status=0
  [[ -s "$project" ]] || { fail "project" "missing"; return; }
  /usr/bin/python3 - "$project" "$files" >"$home/project.txt" <<'PY' || status=$?
import json, sys
p = json.load(open(sys.argv[1]))
pairs = p.get("pairs", [])
effects = [e["effect"] for e in p.get("effects", [])]
layers = p.get("depth", {}).get("layers", [])
print("project: %d pairs, model %s; effects %s; photo %s" % (len(pairs), p.get("model"), effects,
                                                            p.get("photo")))
wrong = []
if p.get("photo") not in ("moved/coffee.png", sys.argv[2] + "/moved/coffee.png"):
    wrong.append("the photo is %s, not the located moved/coffee.png" % p.get("photo"))
depths = []
for layer in layers:
    anchors = layer.get("anchors", [])
    depths.append([a["depth"] for a in anchors])
    print("  depth plane %r: %s" % (layer.get("name"), ", ".join(
        "(%.1f, %.1f) depth %g" % (a["pixel"][0], a["pixel"][1], a["depth"]) for a in anchors)))
if len(pairs) != 9: wrong.append("%d pairs, not 9" % len(pairs))
if effects != ["aerial-perspective", "depth-of-field"]: wrong.append("effects %s" % effects)
if depths != [[1.5, 1.5, 40], [2, 2, 2]]: wrong.append("plane depths %s" % depths)
if wrong:
    print("  the project is not what the session made: " + "; ".join(wrong))
    sys.exit(1)
PY
  while IFS= read -r line; do log "  $line"; done <"$home/project.txt"
  if [[ "$status" -ne 0 ]]; then fail "project contents"; fi
}

# Depth points clicked on the result lie where the result shows them: each saved point's photo
# pixel, mapped by the camera artcam export rendered with, is the result pixel clicked (1.5 px).
check_anchors() {
  [[ -s "$files/cli.artcam" && -s "$project" ]] || { fail "depth points" "no camera"; return; }
  /usr/bin/python3 - "$project" >"$home/anchors.csv" <<'PY'
import json, sys
print("x,y")
for layer in json.load(open(sys.argv[1])).get("depth", {}).get("layers", []):
    for a in layer.get("anchors", []):
        print("%r,%r" % tuple(a["pixel"]))
PY
  "$artcam_bin" map "$files/cli.artcam" "$home/anchors.csv" >"$home/anchors-mapped.csv"
  local status=0
  /usr/bin/python3 "$check" anchors "$home/anchors-mapped.csv" "$anchor_clicks" \
    >"$home/anchors.txt" 2>&1 || status=$?
  while IFS= read -r line; do log "  $line"; done <"$home/anchors.txt"
  if [[ "$status" -ne 0 ]]; then fail "depth points on the result"; fi
}

recovery_files() { find "$XDG_DATA_HOME" -path '*/recovery/*.artcamproj' 2>/dev/null; }

# A second studio while the first has unsaved work and a live recovery file (the autosave runs
# every ARTCAM_AUTOSAVE_INTERVAL_MS): no "Recover work" prompt may come up.
second_instance_check() {
  local w second_pid second_win="" i
  for _ in $(seq 1 50); do
    [[ -n "$(recovery_files)" ]] && break
    sleep 0.2
  done
  if [[ -z "$(recovery_files)" ]]; then
    fail "second instance" "the first studio wrote no recovery file to offer"
    return
  fi
  log "  the first studio's recovery: $(recovery_files | xargs -n 1 basename | tr '\n' ' ')"
  "$studio_bin" >>"$outdir/files/studio-stderr.log" 2>&1 &
  second_pid=$!
  if w="$(wait_window '^Recover work$' 8)"; then
    shot second-instance "a second studio: it offers to recover the first's live work"
    fail "second instance" "the second studio offered the first one's recovery"
    xdotool windowfocus --sync "$w"
    xdotool key Escape
  fi
  for _ in $(seq 1 25); do
    for i in $(xdotool search --onlyvisible --name 'ARTcam Studio$' 2>/dev/null || true); do
      [[ "$i" != "$main_win" ]] && second_win="$i"
    done
    [[ -n "$second_win" ]] && break
    sleep 0.2
  done
  if [[ -n "$second_win" ]]; then
    xdotool windowmove --sync "$second_win" 0 0 || true
    xdotool windowsize --sync "$second_win" "$win_w" "$win_h" || true
    xdotool windowraise "$second_win" 2>/dev/null || true
    [[ "${#failed[@]}" -gt 0 && "${failed[-1]}" == "second instance" ]] ||
      shot second-instance "a second studio started beside the first: no recovery offered"
    xdotool windowfocus --sync "$second_win"
    xdotool key ctrl+q
  else
    note "the second studio's window did not appear"
  fi
  for _ in $(seq 1 50); do kill -0 "$second_pid" 2>/dev/null || break; sleep 0.2; done
  if kill -0 "$second_pid" 2>/dev/null; then
    note "the second studio did not quit; killed"
    kill "$second_pid"
  fi
  wait "$second_pid" 2>/dev/null || true
  xdotool windowraise "$main_win" 2>/dev/null || true
  [[ -n "$(recovery_files)" ]] || note "the first studio's recovery file is gone after the second quit"
}

# The control: a studio on the grid with one unsaved pair is killed (SIGKILL) once its recovery
# file is written; the next studio must offer it.
recovery_control() {
  use_photo "$files/grid.png"
  start_studio "$files/grid.png"
  calibrate quiet
  menu t p
  click_photo 300 300
  click_photo 310 305
  for _ in $(seq 1 50); do
    [[ -n "$(recovery_files)" ]] && break
    sleep 0.2
  done
  kill -KILL "$studio_pid"
  wait "$studio_pid" 2>/dev/null || true
  studio_pid=""
  sleep 1
  xdotool getdisplaygeometry >/dev/null 2>&1 || log "  (the X server is gone after the kill)"
  "$studio_bin" >>"$outdir/files/studio-stderr.log" 2>&1 &
  studio_pid=$!
  if w="$(wait_window '^Recover work$' 10)"; then
    log "  the next studio offers the killed one's work (answered No)"
    xdotool windowfocus --sync "$w"
    xdotool key Escape
  else
    fail "recovery control" "no offer after a killed studio: the second-instance check cannot see one"
  fi
  sleep 1
  kill "$studio_pid" 2>/dev/null || true
  wait "$studio_pid" 2>/dev/null || true
  studio_pid=""
}

# === the session =================================================================================

log "studio-session: $studio_bin on copies of $(basename "$photo_src") and a barrel grid," \
  "display $DISPLAY, output $outdir"
# A display that answers already belongs to another X server: driving it would click on someone
# else's screen, so the session refuses it (and checks the new server's size after the start).
if xdotool getdisplaygeometry >/dev/null 2>&1; then
  log "display $DISPLAY is in use by another X server; name a free one with DISPLAY_NUMBER"
  exit 1
fi
Xvfb "$DISPLAY" -screen 0 "${screen_w}x${screen_h}x24" -nolisten tcp >"$home/xvfb.log" 2>&1 &
xvfb_pid=$!
for _ in $(seq 1 50); do
  xdotool getdisplaygeometry >/dev/null 2>&1 && break
  sleep 0.2
done
if [[ "$(xdotool getdisplaygeometry 2>/dev/null)" != "$screen_w $screen_h" ]]; then
  log "Xvfb did not start on $DISPLAY: $(tail -n 1 "$home/xvfb.log")"
  exit 1
fi
failed=()  # the checks that failed, by name; the session goes on to the end
fail() {
  failed+=("$1")
  log "  FAILED: $1${2:+: $2}"
}

# 1. The studio on the photo's copy.
step "open a photo: the studio on files/coffee.png"
use_photo "$files/coffee.png"
start_studio "$files/coffee.png"
shot start "the photo loaded (Result view of the identity camera)"
calibrate

# 2. Nine pairs of a bulge u' = u / (1 - k r^2) (normalised frame: centre 0, half the longer
# side 1), on a 3x3 grid jittered so no three sources line up, placed corners and centre first
# (so the first few pairs' camera is well posed where the next source lies) on the Result view (Alt+2)
# as a user who looks at the result does: the source is clicked where the result shows the
# photo point (the camera of the pairs so far, made by `artcam fit`, says where), so the studio,
# mapping the click back through its camera's inverse, must record the intended photo point.
step "nine source->target pairs of a bulge (k = 0.12), clicked on the Result view (Alt+2)"
key alt+2
pairs="$(awk -v w="$photo_w" -v h="$photo_h" 'BEGIN {
  split("0.42 0.61 0.35 0.55 0.38 0.66 0.47 0.58 0.33", jx, " ")
  split("0.37 0.52 0.64 0.45 0.58 0.36 0.63 0.41 0.55", jy, " ")
  split("0 8 2 6 4 1 3 5 7", order, " ")
  k = 0.12; s = (w > h ? w : h) / 2
  for (o = 1; o <= 9; ++o) {
    i = order[o] % 3; j = int(order[o] / 3); n = order[o] + 1
    x = w * (0.1 + 0.8 * (i + jx[n]) / 3); y = h * (0.1 + 0.8 * (j + jy[n]) / 3)
    u = (x - w / 2) / s; v = (y - h / 2) / s; f = 1 / (1 - k * (u * u + v * v))
    printf "%.2f %.2f %.2f %.2f\n", x, y, u * f * s + w / 2, v * f * s + h / 2
  }}')"
placed=""  # the pairs as the studio should hold them now, one "sx sy tx ty" a line
# Two pairs are placed wrong on purpose and put right by a drag on the result below, as a user
# corrects a pair: pair 5's target 9 px left and 7 px up of the bulge's, pair 9's source 10 px
# right and 8 px down of the photo point meant.
miss5=(-9 -7) miss9=(10 8)
n=0
while read -r sx sy tx ty; do
  n=$((n + 1))
  calibrate quiet  # a fit's message may resize a dock, and the canvas refits the photo
  if [[ "$n" -eq 5 ]]; then tx="$(calc "$tx + ${miss5[0]}")" ty="$(calc "$ty + ${miss5[1]}")"; fi
  if [[ "$n" -eq 9 ]]; then sx="$(calc "$sx + ${miss9[0]}")" sy="$(calc "$sy + ${miss9[1]}")"; fi
  read -r rx ry < <(result_of "$placed" "$sx" "$sy")
  snapshot_before "$n"
  click_photo "$rx" "$ry"
  click_photo "$tx" "$ty"
  echo "$rx $ry" >>"$home/source-clicks.txt"
  log "  pair $n: source ($sx, $sy), clicked on the result at ($rx, $ry) -> target ($tx, $ty)"
  placed+="$sx $sy $tx $ty"$'\n'
done <<<"$pairs"
snapshot_before 10
shot pairs-result "nine pairs placed on the result (Result view; pairs 5 and 9 misplaced)"

# The drags. A target is a result pixel: pair 5's is grabbed where it shows and dropped on the
# bulge's target. A source is drawn at its photo pixel in every view, and dragged over the result
# it moves by the cursor's motion mapped back through the camera the drag began with (C0):
# grabbed at p, dropped at C0(C0^-1(p) - miss), it must land on the photo point meant, p - miss.
step "drag pair 5's target and pair 9's source on the Result view onto the bulge's points"
want="$(awk -v m="${miss5[*]} ${miss9[*]}" 'BEGIN { split(m, d, " ") }
  NR == 5 { $3 -= d[1]; $4 -= d[2] } NR == 9 { $1 -= d[3]; $2 -= d[4] }
  NF == 4 { printf "%.2f %.2f %.2f %.2f\n", $1, $2, $3, $4 }' <<<"$placed")"$'\n'
read -r sx sy tx ty < <(sed -n 5p <<<"$placed")
read -r _ _ wx wy < <(sed -n 5p <<<"$want")
calibrate quiet
drag_photo "$tx" "$ty" "$wx" "$wy"
log "  pair 5's target dragged on the result from ($tx, $ty) to ($wx, $wy)"
placed="$(awk -v x="$wx" -v y="$wy" 'NR == 5 { $3 = x; $4 = y } NF == 4 { print }' <<<"$placed")"$'\n'
read -r sx sy tx ty < <(sed -n 9p <<<"$placed")
camera_of "$placed" "$home/drag.artcam"
read -r px py < <(/usr/bin/python3 "$check" inverse "$artcam_bin" "$home/drag.artcam" "$sx" "$sy")
read -r dx dy < <(map_point "$home/drag.artcam" "$(calc "$px - ${miss9[0]}")" "$(calc "$py - ${miss9[1]}")")
drag_photo "$sx" "$sy" "$dx" "$dy"
log "  pair 9's source dragged on the result from ($sx, $sy) to ($dx, $dy)"
placed="$want"
key alt+1
shot pairs-photo "the nine pairs as arrows on the photo (Photo view, Alt+1), after the drags"
key alt+2
shot pairs-dragged "the result after the drags: the bulge of nine exact pairs (Result view)"

step "save the project (Ctrl+S: no project path yet, so Save As) to files/session.artcamproj"
project="$files/session.artcamproj"
save_project "$project"
check_pairs

# 3. Straight lines on a barrel grid: File > Open (Ctrl+O) in the same window, the Line tool
# (Tools > Lines), two horizontal and two vertical grid lines clicked at eight points each, Enter
# ending each line; the result must be the grid with its lines SPACING px apart, and the
# studio's camera the one `artcam fit --lines` makes of the same lines.
step "open the barrel grid (Ctrl+O, files/grid.png) and trace 2 horizontal and 2 vertical lines"
key ctrl+o
file_dialog "Open photo or project" "$files/grid.png" || note "no open dialog"
wait_title grid.png 20 || note "the title does not name grid.png"
use_photo "$files/grid.png"
menu t l
calibrate
while read -r name points; do
  calibrate quiet
  for p in ${points}; do
    click_photo "${p%,*}" "${p#*,}"
  done
  key Return
  log "  line $name: $(wc -w <<<"$points") points"
done <"$files/grid-clicks.txt"
shot lines-photo "four traced lines on the grid's photo (the Line tool shows the photo)"
key alt+2
shot lines-result "the straightened grid (Result view) with the lines mapped"

step "export the straightened grid (Ctrl+E), its camera (File > Export Camera) and save"
grid_export="$files/grid-export.png"
export_image "$grid_export" || true
menu f c
file_dialog "Export camera" "$files/grid-studio.artcam" || note "no camera export dialog"
wait_file "$files/grid-studio.artcam" 20 || note "the camera export did not write"
grid_project="$files/grid.artcamproj"
save_project "$grid_project"
shot lines-exported "after the export and the save"
check_lines

# 4. The coffee project again (Ctrl+O), effects first, then depth planes painted on the Result
# view with depth of field showing.
step "reopen files/session.artcamproj (Ctrl+O); aerial perspective and depth of field"
key ctrl+o
file_dialog "Open photo or project" "$project" || note "no open dialog"
wait_title session.artcamproj 20 || note "the title does not name session.artcamproj"
use_photo "$files/coffee.png"
key alt+2
calibrate
click_screen "${effects_tab[@]}"
for initial in a d; do
  click_screen "${effect_combo[@]}"
  sleep 0.3
  xdotool key "$initial"
  sleep 0.2
  xdotool key Return
  sleep 0.3
  key alt+a
done
shot effects "the bulge with aerial perspective and depth of field (no depth yet: no haze)"

# The depth planes: each a polygon (Tools > Depth Polygon, Enter closes) and three depth points
# (Tools > Depth Points) whose depths are typed into the Depth panel's Next depth field before
# each click, all clicked on the result where it shows the photo points meant (the camera made
# by `artcam fit` of the pairs says where). Plane 1 covers the whole result: the table, near at
# the bottom (1.5), far at the top (40). Plane 2 is the cup and saucer at depth 2 (the depth of
# field's focus). The tools are chosen by the menu's mnemonics, not their one-letter shortcuts:
# after typing into a field the keyboard focus is in the panel, where a letter would be typed.
anchor_clicks="$home/anchor-clicks.txt"
: >"$anchor_clicks"
depth_point() {  # depth_point DEPTH X Y: a depth point at photo pixel (X, Y), clicked on the result
  local rx ry
  set_next_depth "$1"
  read -r rx ry < <(result_of "$placed" "$2" "$3")
  click_photo "$rx" "$ry"
  echo "$rx $ry" >>"$anchor_clicks"
}
step "depth plane 1 (table) on the result: Ctrl+Shift+N, polygon over the whole result, depths 1.5, 1.5, 40"
click_screen "${depth_tab[@]}"
key ctrl+shift+n
menu t y
m=2
right=$((photo_w - m)) bottom=$((photo_h - m))
for corner in "$m $m" "$right $m" "$right $bottom" "$m $bottom"; do
  click_photo $corner
done
key Return
menu t o
depth_point 1.5 40 360
depth_point 1.5 560 360
depth_point 40 300 24
shot depth-plane1 "plane 1 painted on the result: the haze shows at once"

step "depth plane 2 (cup and saucer) on the result: polygon around them, depths 2, 2, 2"
key ctrl+shift+n
menu t y
cup=""
for corner in "232 28" "290 16" "350 22" "395 45" "425 65" "445 115" "472 170" "480 240" \
  "462 305" "420 350" "355 382" "290 390" "215 378" "150 350" "100 305" "78 250" "88 180" \
  "120 130" "170 95" "190 55"; do
  cup+="$(result_of "$placed" $corner)"$'\n'
done
while read -r rx ry; do click_photo "$rx" "$ry"; done <<<"${cup%$'\n'}"
key Return
menu t o
depth_point 2 150 250
depth_point 2 430 250
depth_point 2 290 150
shot depth-dof "plane 2 painted on the result while depth of field shows (the cup in focus)"
menu t p
key shift+d
shot depth-overlay "Shift+D: both planes under the depth overlay (red near, blue far)"
key shift+d

# 5. Export; a second studio while this one runs; save; quit.
export1="$files/export-1.png"
export2="$files/export-2.png"
step "export (Ctrl+E) to files/export-1.png"
export_image "$export1" || true

step "a second studio while the first runs with unsaved work: no recovery offer"
second_instance_check

step "save (Ctrl+S) and quit (Ctrl+Q)"
save_project "$project"
quit_studio

# 6. The photo moves; the project reopens through Locate; the export is the same.
step "move the photo (files/coffee.png -> files/moved/coffee.png) and reopen the project"
mkdir -p "$files/moved"
# The project as it was saved, photo and all, for `artcam export --photo` below.
cp "$project" "$files/session-before-move.artcamproj"
mv "$files/coffee.png" "$files/moved/coffee.png"
start_studio "$project" nowait
if w="$(wait_window '^Open project$' 15)"; then
  shot locate-prompt "the project's photo is missing: the prompt offers Locate…"
  xdotool windowfocus --sync "$w"
  sleep 0.3
  xdotool key Return
  if file_dialog "Locate coffee.png" "$files/moved/coffee.png"; then
    wait_title session.artcamproj 20 || note "the title does not name session.artcamproj"
  else
    fail "locate" "no Locate file dialog"
  fi
else
  fail "locate" "no prompt for the missing photo"
fi
sleep 1
calibrate
shot reopened "the project reopened on the located photo: pairs, planes and effects back"
step "export again (Ctrl+E) to files/export-2.png"
export_image "$export2" || true
step "save (Ctrl+S: the project now names the photo's new place) and quit"
save_project "$project"
quit_studio

# 7. The comparisons. compare -metric AE prints how many pixels differ (exit status 1 when any).
step "compare the exports with each other and with artcam export --photo"
check_project
cli_status=0
"$artcam_bin" export "$files/session-before-move.artcamproj" --photo "$files/moved/coffee.png" \
  -o "$files/cli-photo.png" --quiet --overwrite >"$home/cli.txt" 2>&1 || cli_status=$?
while IFS= read -r line; do log "  artcam export --photo: $line"; done <"$home/cli.txt"
if [[ "$cli_status" -ne 0 ]]; then fail "artcam export --photo" "exit status $cli_status"; fi
cli_status=0
"$artcam_bin" export "$project" -o "$files/cli.png" --camera-out "$files/cli.artcam" --quiet \
  --overwrite >"$home/cli.txt" 2>&1 || cli_status=$?
while IFS= read -r line; do log "  artcam export: $line"; done <"$home/cli.txt"
if [[ "$cli_status" -ne 0 ]]; then fail "artcam export" "exit status $cli_status"; fi
compare_pair "$export1" "$export2"
compare_pair "$export1" "$files/cli-photo.png"
compare_pair "$export1" "$files/cli.png"
# The export must not be the photo itself (a session whose edits never arrived would still give
# three identical exports).
if [[ -s "$export1" ]]; then
  ae="$(compare -metric AE "$export1" "$files/moved/coffee.png" null: 2>&1)" || true
  log "  export-1.png vs the photo: $ae pixels differ (the warp and the effects)"
  if [[ "$ae" == "0" ]]; then fail "export-1.png is the photo"; fi
fi
check_anchors

# 8. The recovery check's own check: a studio killed with unsaved work does leave its recovery,
# and the next studio offers it, so the second-instance check above can see an offer.
step "control: a studio killed with unsaved work is offered for recovery to the next one"
recovery_control

if [[ "${#failed[@]}" -ne 0 ]]; then
  log "studio-session: FAILED: ${failed[*]}; $notes note(s); shots in $outdir"
  exit 1
fi
log "studio-session: done, $shot_n shots, $notes note(s), every check passed; see $outdir"
