# SPDX-License-Identifier: Apache-2.0
# bash completion for artcam(1), installed as /usr/share/bash-completion/completions/artcam.
# Completes the commands, bench's sub-commands, each command's options and their values, preset
# names and a preset's parameters. The option lists mirror the parsers' OptionSpec lists in
# app/cli/cmd_<command>*.cpp; tests/app/test_cli_completions.cpp fails when one is missing here
# or in _artcam (zsh). Preset names and parameters are asked of `artcam preset list` at
# completion time, so they follow the effects table without an edit here. Plain bash: it needs
# neither the bash-completion package's helpers nor a particular bash-completion version.

_artcam_commands="fit map warp batch info bench render preset compose export export-map lens
                  insert sample stereo unfold"

# The options of one page: a command, or bench's sub-command ("bench fit").
_artcam_options() {
  case "$1" in
    fit) echo "--output -o --size --target-size --model --dim --no-refine --robust --threshold
               --allow-poles --json --block --srgb --piecewise --max-error --overwrite --force
               --quiet -q --stmap --layer --lines --flat-field --cells" ;;
    map) echo "--json" ;;
    warp) echo "--output -o --format --size --filter --edge --subsampling --threads --quality --bit-depth
                --colourspace --colourspace-in --colourspace-out
                --stats --json --overwrite --force --quiet -q --depth --depth-scale --disparity
                --second --finish" ;;
    batch) echo "--output -o --suffix --format --first --frames --chunk --skip-existing --finish --size --filter --edge --subsampling --threads --quality
                 --bit-depth --colourspace --colourspace-in --colourspace-out --overwrite --force --json --quiet -q
                 --lens-from-exif" ;;
    info) echo "--json" ;;
    "bench render") echo "--size --reps --threads --plot --peer --only --filter --type --no-e2e
                          --no-suite --cameras --overwrite --force" ;;
    "bench fit") echo "--counts --noise --plot --seconds --methods --colour --overwrite --force" ;;
    "bench effects") echo "--size --crop --sigmas --reps --threads --image --ratio --shrink-from
                           --only" ;;
    render) echo "--output -o --view --eye --at --fov --size --layers --point-size --splat-scale
                  --threads --stats --json --overwrite --force --quiet -q" ;;
    preset) echo "--output -o --overwrite --force --size" ;;
    compose) echo "--output -o --force --overwrite --json" ;;
    export) echo "--output -o --photo --camera-out --depth-out --size --filter --edge --subsampling --quality --bit-depth --colourspace --colourspace-in --colourspace-out
                  --crop-valid --fill --finish --json --overwrite --force --quiet -q" ;;
    export-map) echo "--output -o --size --convention --source-size --json --overwrite --force" ;;
    lens) echo "--limit --json --lens --from --focal --crop --size --output -o --distort --no-tca
                --aperture --distance --no-vignetting --max-error --overwrite --force" ;;
    insert) echo "--output -o --matches --camera --canonical --table --grid-on-table --region
                  --max-error --save-camera --mesh-step --overwrite --force --quiet -q" ;;
    sample) echo "--output -o --squares --size --overwrite --force --quiet -q" ;;
    stereo) echo "--output -o --baseline-focal --max-disparity --block --overwrite --force --json" ;;
    unfold) echo "--output -o --depth --walls --focal --principal --scale --no-roof --overwrite --force --json" ;;
  esac
}

# Preset names (lines of `artcam preset list` that start with two spaces and a name), or with a
# name, that preset's parameters as options (its "param=default" words).
_artcam_presets() {
  "$1" preset list 2>/dev/null | awk -v want="$2" '
    /^  [^ ]/ { name = $1; if (want == "") print name; next }
    want != "" && name == want {
      for (i = 1; i <= NF; i++) if (split($i, kv, "=") == 2) print "--" kv[1]
    }'
}

# The values an option takes, as the page's --help spells them ("--filter nearest|bilinear|
# bicubic"), asked of artcam at completion time like the presets, so they follow the parsers.
_artcam_values() {
  # $2 unquoted: "bench render" is two words.
  "$1" $2 --help 2>/dev/null | grep -o -- "$3 [a-z0-9.]*\(|[a-z0-9.]*\)\+" | cut -d' ' -f2 |
    tr '|' '\n' | sort -u
}

_artcam() {
  local cur="${COMP_WORDS[COMP_CWORD]}"
  local artcam="${COMP_WORDS[0]}"
  COMPREPLY=()
  if [[ $COMP_CWORD -eq 1 ]]; then
    COMPREPLY=($(compgen -W "$_artcam_commands help --help -h --version" -- "$cur"))
    return 0
  fi
  local command="${COMP_WORDS[1]}" page="${COMP_WORDS[1]}"
  case "$command" in
    bench)
      if [[ $COMP_CWORD -eq 2 && "$cur" != -* ]]; then
        COMPREPLY=($(compgen -W "render fit effects" -- "$cur"))
        return 0
      fi
      case "${COMP_WORDS[2]}" in
        fit|effects) page="bench ${COMP_WORDS[2]}" ;;
        *) page="bench render" ;;  # bench without a sub-command is bench render
      esac
      ;;
    lens)
      if [[ $COMP_CWORD -eq 2 && "$cur" != -* ]]; then
        COMPREPLY=($(compgen -W "search camera" -- "$cur"))
        return 0
      fi
      ;;
    preset)
      if [[ $COMP_CWORD -eq 2 && "$cur" != -* ]]; then
        COMPREPLY=($(compgen -W "list $(_artcam_presets "$artcam")" -- "$cur"))
        return 0
      fi
      ;;
  esac
  if [[ $COMP_CWORD -ge 2 && "${COMP_WORDS[COMP_CWORD-1]}" == --* ]]; then
    local values
    values="$(_artcam_values "$artcam" "$page" "${COMP_WORDS[COMP_CWORD-1]}")"
    if [[ -n "$values" ]]; then
      COMPREPLY=($(compgen -W "$values" -- "$cur"))
      return 0
    fi
  fi
  if [[ "$cur" == -* ]]; then
    local options
    options="$(_artcam_options "$page") --help -h"
    [[ "$command" == preset && $COMP_CWORD -gt 2 ]] &&
      options+=" $(_artcam_presets "$artcam" "${COMP_WORDS[2]}")"
    # An effect's size=WxH parameter is also the static --size: offer each name once.
    COMPREPLY=($(compgen -W "$(printf '%s\n' $options | sort -u)" -- "$cur"))
    return 0
  fi
  # Operands and option values are files (cameras, photos, CSV, outputs) or free text.
  compopt -o filenames 2>/dev/null
  COMPREPLY=($(compgen -f -- "$cur"))
  return 0
}

complete -F _artcam artcam
