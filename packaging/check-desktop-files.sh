#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Validates the desktop integration in packaging/desktop/: the .desktop entry
# (desktop-file-validate), the AppStream metainfo (appstreamcli validate --no-net), the MIME XML
# (compiled by update-mime-database into a scratch database), and that they agree with each
# other (the MIME types the entry lists exist, the icon and the launchable are there).
# A missing validator is a failure, not a pass: packaging/install-deps.sh installs them.
set -euo pipefail
dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/desktop"
id=org.artcam.Studio
fail() { echo "check-desktop-files: $*" >&2; exit 1; }
for tool in desktop-file-validate appstreamcli update-mime-database xmllint; do
  command -v "$tool" >/dev/null || fail "$tool not found (run packaging/install-deps.sh)"
done

# Hints (suggestions) pass; errors and warnings fail.
out="$(desktop-file-validate "$dir/$id.desktop" 2>&1)" || fail "$id.desktop is not valid: $out"
if grep -v ': hint: ' <<<"$out" | grep -q .; then fail "$id.desktop: $out"; fi
appstreamcli validate --no-net --pedantic "$dir/$id.metainfo.xml" \
  || fail "$id.metainfo.xml is not valid"

xmllint --noout "$dir/$id.mime.xml" || fail "$id.mime.xml is not well-formed"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/mime/packages"
cp "$dir/$id.mime.xml" "$scratch/mime/packages/$id.xml"
XDG_DATA_DIRS="$scratch:/usr/share" update-mime-database "$scratch/mime" 2>"$scratch/err" || fail "update-mime-database: $(cat "$scratch/err")"
[[ -s "$scratch/err" ]] && fail "update-mime-database warned: $(cat "$scratch/err")"
grep -q ':application/x-artcam+json:\*\.artcam$' "$scratch/mime/globs2" || fail "no *.artcam glob"
grep -q ':application/x-artcam-project+json:\*\.artcamproj$' "$scratch/mime/globs2" \
  || fail "no *.artcamproj glob"

# Every application/x-artcam* type the entry opens is one the XML defines.
types="$(sed -n 's/^MimeType=//p' "$dir/$id.desktop" | tr ';' '\n' | grep '^application/x-artcam' || true)"
[[ $(wc -w <<<"$types") -eq 2 ]] || fail "$id.desktop should list both ARTcam MIME types, has: $types"
for t in $types; do grep -q "type=\"$t\"" "$dir/$id.mime.xml" || fail "$t is not in $id.mime.xml"; done
# Every photo format the studio's Open dialog offers (kPhotoPatterns in ui/session.cpp) is one
# the entry claims, so a file manager offers the studio for each: extension -> MIME type by the
# system's shared-mime-info globs.
patterns="$(sed -n '/^const char kPhotoPatterns\[\] =/,/;$/p' "$dir/../../ui/session.cpp" |
  grep -o '\*\.[a-z0-9]*' | sed 's/^\*\.//')"
[[ $(wc -w <<<"$patterns") -ge 10 ]] || fail "cannot read kPhotoPatterns from ui/session.cpp"
claimed=";$(sed -n 's/^MimeType=//p' "$dir/$id.desktop")"
for ext in $patterns; do
  mime="$(awk -F: -v g="*.$ext" '$3 == g { print $2; exit }' /usr/share/mime/globs2)"
  [[ -n "$mime" ]] || continue  # no system type names it (DPX, Radiance HDR): nothing to claim
  [[ "$claimed" == *";$mime;"* ]] || fail "$id.desktop opens *.$ext in the studio but its MimeType lacks $mime"
done
grep -qx "Icon=$id" "$dir/$id.desktop" || fail "$id.desktop does not name the icon $id"
[[ -f "$dir/icons/$id.svg" ]] || fail "icons/$id.svg missing"
grep -q "<launchable type=\"desktop-id\">$id.desktop</launchable>" "$dir/$id.metainfo.xml" \
  || fail "$id.metainfo.xml does not launch $id.desktop"
echo "check-desktop-files: $id.desktop, $id.metainfo.xml and $id.mime.xml are valid and agree"
