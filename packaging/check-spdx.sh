#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Every source file of the project opens with its licence, `SPDX-License-Identifier: Apache-2.0`
# as a comment on the first line (the second after a `#!` or zsh's `#compdef` line, which must
# come first): C++ sources and headers, CMake files, shell and Python scripts, the completions. Data files, images, JSON, Markdown and the fuzz corpora carry
# none (resources/README.md names the assets' licences).
# Usage: bash packaging/check-spdx.sh          lists the files without the line; fails if any
#        bash packaging/check-spdx.sh --fix    inserts the line into those files and nothing else
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
fix=0
[[ "${1:-}" == "--fix" ]] && fix=1
id="SPDX-License-Identifier: Apache-2.0"

# The tracked files when this is a git checkout (so build trees and scratch files are not
# scanned); otherwise, as in an unpacked source tarball, the same folders on disk.
cd "$root"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files -- core ui app tests fuzz packaging cmake resources \
    CMakeLists.txt | grep -E '(\.(h|cpp|cmake|sh|bash|py)|(^|/)CMakeLists\.txt|^packaging/completions/.*)$' |
    grep -v '^fuzz/corpus/')
else
  mapfile -t files < <(find core ui app tests fuzz packaging cmake resources CMakeLists.txt \
    -path fuzz/corpus -prune -o -type f \
    \( -name '*.h' -o -name '*.cpp' -o -name '*.cmake' -o -name '*.sh' -o -name '*.bash' \
       -o -name '*.py' -o -name CMakeLists.txt -o -path 'packaging/completions/*' \) -print | sort)
fi
[[ ${#files[@]} -gt 0 ]] || { echo "check-spdx: no source files found under $root" >&2; exit 1; }

missing=()
for f in "${files[@]}"; do
  [[ -f "$f" ]] || continue  # deleted in the work tree, not yet in the index
  first="$(head -n 1 "$f")"
  line="$first"
  header=0
  [[ "$first" == '#!'* || "$first" == '#compdef '* ]] && header=1
  [[ $header -eq 1 ]] && line="$(sed -n 2p "$f")"
  case "$f" in
    *.h|*.cpp) want="// $id" ;;
    *) want="# $id" ;;
  esac
  [[ "$line" == "$want" ]] && continue
  missing+=("$f")
  if [[ $fix -eq 1 ]]; then
    # One line inserted and nothing else changed, so the edit merges cleanly with other work.
    if [[ $header -eq 1 ]]; then
      sed -i "1a $want" "$f"
    else
      sed -i "1i $want" "$f"
    fi
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "check-spdx: ${#files[@]} source files carry '$id'"
  exit 0
fi
if [[ $fix -eq 1 ]]; then
  printf 'check-spdx: added the line to %s\n' "${missing[@]}"
  exit 0
fi
printf 'check-spdx: %s: first line is not the SPDX line\n' "${missing[@]}" >&2
echo "check-spdx: ${#missing[@]} of ${#files[@]} source files lack '$id';" \
  "bash packaging/check-spdx.sh --fix adds it" >&2
exit 1
