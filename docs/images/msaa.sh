#!/usr/bin/env bash
# Anti-aliasing before and after: the STS cab view 40 s into the discharge drawn with one sample a pixel and
# with four, the same part of each enlarged 4x (nearest neighbour) side by side: docs/images/msaa_before_after.png.
# Usage: docs/images/msaa.sh [path/to/harboursim]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
app="${1:-$here/../../build/release/apps/harboursim/harboursim}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for samples in 0 4; do
  "$app" screenshot --exercise sts_discharge --at 40 --view cab --size 640x360 --multisamples "$samples" \
    --out "$work/$samples.png" > /dev/null
done
enlarge="crop=140:90:260:140,scale=560:360:flags=neighbor"
ffmpeg -loglevel error -y -i "$work/0.png" -i "$work/4.png" \
  -filter_complex "[0]$enlarge[a];[1]$enlarge[b];[a][b]hstack" "$here/msaa_before_after.png"
echo "$here/msaa_before_after.png"
