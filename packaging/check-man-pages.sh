#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Formats every manual page in docs/man/ with groff's man macros and all warnings on
# (-ww); any diagnostic fails. Usage: bash packaging/check-man-pages.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command -v groff >/dev/null || { echo "check-man-pages: groff not found (apt-get install groff-base)" >&2; exit 1; }
pages=("$root"/docs/man/*.1)
[[ -f "${pages[0]}" ]] || { echo "check-man-pages: no pages in $root/docs/man" >&2; exit 1; }
for page in "${pages[@]}"; do
  diagnostics="$(LC_ALL=C.UTF-8 groff -man -Tutf8 -ww -z "$page" 2>&1)"
  if [[ -n "$diagnostics" ]]; then
    echo "check-man-pages: $page:" >&2
    echo "$diagnostics" >&2
    exit 1
  fi
  # Plain ASCII input: groff without preconv reads bytes as Latin-1, so other characters break.
  if LC_ALL=C grep -n '[^ -~]' "$page" >&2; then
    echo "check-man-pages: $page has non-ASCII characters (use groff escapes such as \\(mu)" >&2
    exit 1
  fi
done
echo "check-man-pages: ${#pages[@]} pages format without warnings"
