#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs what ARTcam Studio needs to build and run on Debian 12, from Debian's packages.
# Skips apt entirely when everything is already there. Run as root (or with sudo available).
set -euo pipefail

packages=(build-essential cmake ninja-build ccache pkg-config
  qt6-base-dev libgl-dev libeigen3-dev libopenimageio-dev openimageio-tools nlohmann-json3-dev
  libexiv2-dev libjpeg62-turbo-dev liblcms2-dev liblensfun-dev liblensfun-data-v1 libheif-dev
  # OpenCV's semi-global stereo matcher (artcam stereo): the three component packages it needs.
  libopencv-calib3d-dev libopencv-imgproc-dev libopencv-core-dev
  # G'MIC's filters for the finishing marks (--finish pencil, charcoal, painting, cartoon).
  libgmic-dev
  # Peers the tests compare with (their tests fail without them): Hugin's fulla for the edge modes,
  # exiftool for the metadata of HEIC/AVIF/WebP outputs.
  hugin-tools libimage-exiftool-perl
  # fish, to run the fish completion in tests/app/test_cli_completions.cpp; ffmpeg makes the
  # real movie clips tests/app/test_cli_movies.cpp checks are refused.
  fish ffmpeg
  # jq reads the JSON that `artcam fit -o -` pipes out in tests/app/test_cli_streams.cpp.
  jq
  # The hostile corpus (CTest hostile/corpus) is driven by python3; oiiotool makes its images.
  # The README's Python example (CTest docs/code_blocks) reads arrays with numpy and OpenImageIO;
  # the user guide's ST-map recipe warps with OpenCV's remap.
  python3 python3-numpy python3-openimageio python3-opencv
  # `import artcam` (python/): pybind11 builds it; pytest runs its tests, dask.distributed the
  # cluster half (artcam.dask) and its LocalCluster tests.
  pybind11-dev python3-dev python3-pytest python3-distributed
  # CI's fuzzing job (packaging/ci-sanitizers.sh): libFuzzer comes with clang's runtime.
  clang-14 libclang-rt-14-dev
  # Validators of the desktop files and manual pages (CTest packaging/*); file is for cpack's DEB.
  desktop-file-utils appstream shared-mime-info libxml2-utils groff-base file
  # djpeg, cjpeg and GNU time for packaging/bench-warp-codec.sh (the codec floor it compares with).
  libjpeg-turbo-progs time)
# --with-display adds what the screenshot/demo path needs to show a window without a screen, and
# what packaging/studio-session.sh drives it with (xdotool) and shoots and compares it with
# (imagemagick: import, convert, compare).
# The screenshot and picture generators (python3: resources/lines/make_lines_figure.py and the
# screenshot scripts) run with --with-display.
if [[ "${1:-}" == "--with-display" ]]; then packages+=(xvfb xauth xdotool imagemagick python3); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
