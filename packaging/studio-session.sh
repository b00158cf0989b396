#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A scripted session in the REAL artcam-studio window under Xvfb, driven by xdotool the way a
# user drives it: mouse clicks at photo points, keyboard shortcuts, menus by their mnemonics,
# file dialogs by typing a path. It leaves numbered screenshots and a log of every step in
# OUTDIR and fails when the studio's two exports (before and after save, quit and reopen) and
# `artcam export` of the saved project differ.
#
# Usage: bash packaging/studio-session.sh [OUTDIR]      (default: build/studio-session)
# Environment: STUDIO, ARTCAM (the binaries; default build/app/...), DISPLAY_NUMBER (default: the
# first free of :90...:99), STEP_WAIT (seconds a render gets before a shot, default 2).
# Needs the Debian packages xvfb, xdotool and imagemagick (install-deps.sh --with-display).
#
# The session: open a copy of resources/coffee.png; place nine source->target pairs of a bulge;
# flip before/after with \; paint two depth planes with the polygon tool and give each three
# depth points; add aerial perspective and depth of field; export, save, quit, reopen the saved
# project, export again; compare the exports with each other and with `artcam export`.
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
read -r photo_w photo_h < <(identify -format '%w %h\n' "$files/coffee.png")

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

start_studio() {  # start_studio FILE: the studio on FILE, window placed and sized, loaded
  "$studio_bin" "$1" >>"$outdir/files/studio-stderr.log" 2>&1 &
  studio_pid=$!
  find_main_window || { log "the studio window did not appear"; exit 1; }
  xdotool windowmove --sync "$main_win" 0 0 || true
  xdotool windowsize --sync "$main_win" "$win_w" "$win_h" || true
  local g
  g="$(xdotool getwindowgeometry "$main_win" | tr '\n' ' ' | sed 's/  */ /g')"
  log "  window $main_win: $g"
  # The photo loads in a worker; the title names the file once it is in.
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
depth_tab=(1064 863)
effects_tab=(1128 863)
effect_combo=(1112 86)

set_next_depth() {  # the Depth panel's "Next depth" spin box: the depth of the next clicked point
  key alt+n
  xdotool key ctrl+a
  xdotool type --delay 30 "$1"
  xdotool key Tab
  sleep 0.3
}

# === the session =================================================================================

log "studio-session: $studio_bin on a copy of $(basename "$photo_src")" \
  "(${photo_w}x${photo_h}), display $DISPLAY, output $outdir"
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

# 1. The studio on the photo's copy.
step "start the studio on files/coffee.png"
start_studio "$files/coffee.png"
shot start "the photo loaded (Result view of the identity camera)"
calibrate

# 2. Nine pairs of a bulge u' = u / (1 - k r^2) (normalised frame: centre 0, half the longer
# side 1), on a 3x3 grid jittered so no three sources line up. Sources are placed where the
# canvas shows the photo, so the pairs are clicked in the Photo view (Alt+1).
step "nine source->target pairs of a bulge (k = 0.12), clicked in the Photo view (Alt+1)"
key alt+1
pairs="$(awk -v w="$photo_w" -v h="$photo_h" 'BEGIN {
  split("0.42 0.61 0.35 0.55 0.38 0.66 0.47 0.58 0.33", jx, " ")
  split("0.37 0.52 0.64 0.45 0.58 0.36 0.63 0.41 0.55", jy, " ")
  k = 0.12; s = (w > h ? w : h) / 2; n = 0
  for (j = 0; j < 3; ++j) for (i = 0; i < 3; ++i) {
    ++n
    x = w * (0.1 + 0.8 * (i + jx[n]) / 3); y = h * (0.1 + 0.8 * (j + jy[n]) / 3)
    u = (x - w / 2) / s; v = (y - h / 2) / s; f = 1 / (1 - k * (u * u + v * v))
    printf "%.2f %.2f %.2f %.2f\n", x, y, u * f * s + w / 2, v * f * s + h / 2
  }}')"
n=0
while read -r sx sy tx ty; do
  n=$((n + 1))
  calibrate quiet  # a fit's message may resize a dock, and the canvas refits the photo
  click_photo "$sx" "$sy"
  click_photo "$tx" "$ty"
  log "  pair $n: ($sx, $sy) -> ($tx, $ty)"
done <<<"$pairs"
shot pairs-photo "nine pairs drawn as arrows on the photo (Photo view)"
key alt+2
shot pairs-result "the warped result (Result view, Alt+2) with the pairs"

# 3. Before/after.
step "before/after with \\"
key backslash
shot before "\\ once: the photo (before)"
key backslash
shot after "\\ again: the result (after)"

# 4. Two depth planes: each a polygon (Tools > Depth Polygon, Enter closes) and three depth
# points (Tools > Depth Points) whose depths are typed into the Depth panel's Next depth field
# before each click. Plane 1 covers the whole photo: the table, near at the bottom (1.5), far at
# the top (40; that point sits on the top rows, so the plane's horizon stays above the photo).
# Plane 2, on top, is the cup and saucer at depth 2 (the focus of the depth of field below).
# The tools are chosen by the menu's mnemonics, not their one-letter shortcuts:
# after typing into a field the keyboard focus is in the panel, where a letter would be typed.
step "depth plane 1 (table): Ctrl+Shift+N, polygon over the whole photo, depths 1.5, 1.5, 40"
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
set_next_depth 1.5
click_photo 40 370
click_photo 560 370
set_next_depth 40
click_photo 300 8
shot depth-plane1 "plane 1: the table region and its three depth points"

step "depth plane 2 (cup and saucer): Ctrl+Shift+N, polygon around them, depths 2, 2, 2"
key ctrl+shift+n
menu t y
for corner in "232 28" "290 16" "350 22" "395 45" "425 65" "445 115" "472 170" "480 240" \
  "462 305" "420 350" "355 382" "290 390" "215 378" "150 350" "100 305" "78 250" "88 180" \
  "120 130" "170 95" "190 55"; do
  click_photo $corner
done
key Return
menu t o
set_next_depth 2
click_photo 150 250
click_photo 430 250
click_photo 290 150
shot depth-plane2 "plane 2 with its three depth points (a depth tool tints the active plane cyan)"
# The overlay is on by default (View > Show Depth Overlay, Shift+D) and drawn where the photo
# shows; with the pair tool in the Photo view no depth tool's tint covers it. Shift+D hides it.
menu t p
key alt+1
shot depth-overlay "both planes under the depth overlay (red near, blue far) and its legend"
key shift+d
shot depth-overlay-off "Shift+D: the overlay hidden"
key shift+d

# 5. Effects: the Effects dock's combo box (keyboard search: "a" is aerial-perspective, "d"
# depth-of-field, the only entries with those first letters) and its Add button (Alt+A). The
# defaults suit the planes' depths: haze from depth 1 to 100, focus at 2.
step "effects: aerial perspective and depth of field, with their default parameters"
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
key alt+2
shot effects "the result with the bulge, aerial perspective and depth of field (Effects dock)"

# 6. Export, save, quit, reopen, export again.
export1="$files/export-1.png"
export2="$files/export-2.png"
project="$files/session.artcamproj"
step "export (Ctrl+E) to files/export-1.png"
export_image "$export1" || true
shot exported "after the export"

step "save the project (Ctrl+S: no project path yet, so Save As) to files/session.artcamproj"
key ctrl+s
if file_dialog "Save project" "$project" && wait_file "$project" 20; then
  log "  saved $(wc -c <"$project") bytes"
else
  note "the save dialog or the project file did not appear"
fi
shot saved "after the save (the title loses its modified mark)"

step "quit (Ctrl+Q)"
key ctrl+q
if ! wait_exit 10; then
  if w="$(wait_window '^Unsaved changes$' 1)"; then
    note "the studio asked to save unsaved changes after the save; answered Discard"
    xdotool windowfocus --sync "$w"
    xdotool key alt+d
  fi
  if ! wait_exit 10; then
    note "the studio did not quit; killed"
    kill "$studio_pid"
    wait_exit 5 || true
  fi
fi

step "reopen the saved project"
start_studio "$project"
shot reopened "the saved project reopened: pairs, planes and effects back"
step "export again (Ctrl+E) to files/export-2.png"
export_image "$export2" || true
shot reexported "after the second export"
key ctrl+q
if ! wait_exit 10; then
  note "the reopened studio did not quit; killed"
  kill "$studio_pid"
  wait_exit 5 || true
fi

# 7. The comparisons. compare -metric AE prints how many pixels differ (exit status 1 when any).
step "compare the exports, and artcam export of the saved project"
# The saved project is the record of what the clicks and keys did: it must hold nine pairs, the
# two planes with the typed depths and the two effects (a missed click shows up here).
differ=0
if [[ -s "$project" ]]; then
  project_check=0
  python3 - "$project" >"$home/project.txt" <<'PY' || project_check=$?
import json, sys
p = json.load(open(sys.argv[1]))
pairs = p.get("pairs", [])
effects = [e["effect"] for e in p.get("effects", [])]
layers = p.get("depth", {}).get("layers", [])
print("project: %d pairs, model %s; effects %s" % (len(pairs), p.get("model"), effects))
depths = []
for layer in layers:
    anchors = layer.get("anchors", [])
    depths.append([a["depth"] for a in anchors])
    print("  depth plane %r: %s" % (layer.get("name"), ", ".join(
        "(%.1f, %.1f) depth %g" % (a["pixel"][0], a["pixel"][1], a["depth"]) for a in anchors)))
wrong = []
if len(pairs) != 9: wrong.append("%d pairs, not 9" % len(pairs))
if effects != ["aerial-perspective", "depth-of-field"]: wrong.append("effects %s" % effects)
if depths != [[1.5, 1.5, 40], [2, 2, 2]]: wrong.append("plane depths %s" % depths)
if wrong:
    print("  the project is not what the session made: " + "; ".join(wrong))
    sys.exit(1)
PY
  while IFS= read -r line; do log "  $line"; done <"$home/project.txt"
  if [[ "$project_check" -ne 0 ]]; then differ=1; fi
  cli_status=0
  "$artcam_bin" export "$project" -o "$files/cli.png" --quiet --overwrite >"$home/cli.txt" 2>&1 ||
    cli_status=$?
  while IFS= read -r line; do log "  artcam export: $line"; done <"$home/cli.txt"
  if [[ "$cli_status" -ne 0 ]]; then log "  artcam export failed (exit status $cli_status)"; fi
else
  log "  no saved project"
  differ=1
fi
compare_pair() {  # compare_pair A B: logs the number of differing pixels; 0 when none
  if [[ ! -s "$1" || ! -s "$2" ]]; then
    log "  $(basename "$1") vs $(basename "$2"): missing"
    differ=1
    return
  fi
  local ae status=0
  ae="$(compare -metric AE "$1" "$2" null: 2>&1)" || status=$?
  log "  $(basename "$1") vs $(basename "$2"): $ae pixels differ"
  if [[ "$status" -ne 0 ]]; then differ=1; fi
}
compare_pair "$export1" "$export2"
compare_pair "$export1" "$files/cli.png"
# The export must not be the photo itself (a session whose edits never arrived would still give
# three identical exports).
if [[ -s "$export1" ]]; then
  ae="$(compare -metric AE "$export1" "$files/coffee.png" null: 2>&1)" || true
  log "  export-1.png vs the photo: $ae pixels differ (the warp and the effects)"
  if [[ "$ae" == "0" ]]; then differ=1; fi
fi

if [[ "$differ" -ne 0 ]]; then
  log "studio-session: FAILED: the exports differ or are missing, or the project lacks a step;" \
    "$notes note(s); shots in $outdir"
  exit 1
fi
log "studio-session: done, $shot_n shots, $notes note(s), identical exports; see $outdir"
