#!/usr/bin/env bash
# Each machine's cab view (top row) and chase view (bottom row) at one moment of its main exercise in six
# conditions — noon, dusk (18:18, the sun 3.5° down), night (22 h), fog (200 m), rain (20 mm/h) and a storm
# (26 m/s wind, Beaufort 10, 40 mm/h, 2 km visibility) — side by side: docs/images/weather_<exercise>.png; and the sky
# through an evening from the quay (12, 16, 17:30, 18, 18:12, 18:30, 18:48, 19:12 h): docs/images/sky_evening.png;
# the harbour's water from 25 m at 12 m/s and 24 m/s (gusting to 14 and 28 m/s): docs/images/whitecaps.png;
# fair-weather cloud from the quay at 2, 4 and 7 oktas: docs/images/clouds.png; 3 oktas towards the evening
# sun at noon and at 17:36: docs/images/clouds_dusk.png; its shade on the quay at 4
# oktas from 500 m up, a minute apart: docs/images/cloud_shade.png.
# Drawn with surface detail (a GPU station's default) on any renderer.
# Usage: docs/images/weather.sh [path/to/harboursim]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
app="${1:-$here/../../build/release/apps/harboursim/harboursim}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
conditions=(noon dusk night fog rain storm)
options() {  # condition
  case "$1" in
    noon) echo "--time-of-day 12" ;;
    dusk) echo "--time-of-day 18.3" ;;
    night) echo "--time-of-day 22" ;;
    fog) echo "--time-of-day 12 --visibility 200" ;;
    rain) echo "--time-of-day 12 --rain 20 --visibility 3000" ;;
    storm) echo "--time-of-day 15 --rain 40 --visibility 2000 --command 0:wind:26:270:0.15" ;;
  esac
}
shoot() {  # exercise, moment [s]
  local exercise="$1" at="$2" frames=()
  for view in cab chase; do
    for c in "${conditions[@]}"; do
      # shellcheck disable=SC2046
      "$app" screenshot --exercise "$exercise" --at "$at" --view "$view" --size 320x180 --surface-detail true $(options "$c") \
        --out "$work/$view-$c.png" > /dev/null
      frames+=(-i "$work/$view-$c.png")
    done
  done
  ffmpeg -loglevel error -y "${frames[@]}" -filter_complex \
    "[0][1][2][3][4][5]hstack=6[cab];[6][7][8][9][10][11]hstack=6[chase];[cab][chase]vstack" \
    "$here/weather_$exercise.png"
  echo "$here/weather_$exercise.png"
}
shoot sts_discharge 12
shoot rtg_rehandle 20
shoot mhc_coal_discharge 40
shoot reach_stacker_stack 30
shoot tractor_semi_reverse 30
shoot straddle_carrier_stack 40
frames=()
for t in 12 16 17.5 18 18.2 18.5 18.8 19.2; do
  "$app" screenshot --exercise sts_discharge --at 1 --view free --camera=-120,-80,20,60,8 --size 400x225 \
    --time-of-day "$t" --out "$work/sky-$t.png" > /dev/null
  frames+=(-i "$work/sky-$t.png")
done
ffmpeg -loglevel error -y "${frames[@]}" -filter_complex "[0][1][2][3]hstack=4[a];[4][5][6][7]hstack=4[b];[a][b]vstack" \
  "$here/sky_evening.png"
echo "$here/sky_evening.png"
# free views of sts_discharge stacked into one picture: stacked NAME SIZE CAMERA OPTIONS... (each OPTIONS one
# frame's own screenshot options, in one word)
stacked() {
  local name="$1" size="$2" camera="$3" n=0 inputs="" frames=()
  shift 3
  for options in "$@"; do
    # shellcheck disable=SC2086
    "$app" screenshot --exercise sts_discharge --view free --camera="$camera" --size "$size" $options \
      --out "$work/$name-$n.png" > /dev/null
    frames+=(-i "$work/$name-$n.png")
    inputs+="[$n]"
    n=$((n + 1))
  done
  ffmpeg -loglevel error -y "${frames[@]}" -filter_complex "${inputs}vstack=$n" "$here/$name.png"
  echo "$here/$name.png"
}
stacked whitecaps 640x360 60,-40,25,60,-20 "--at 5 --command 0:wind:12:270:0.15" "--at 5 --command 0:wind:24:270:0.15"
stacked clouds 480x270 -120,-80,20,60,25 "--at 1 --cloud 2" "--at 1 --cloud 4" "--at 1 --cloud 7"
stacked clouds_dusk 480x270 -120,-80,20,-90,15 "--at 1 --cloud 3 --time-of-day 12" "--at 1 --cloud 3 --time-of-day 17.6"
stacked cloud_shade 640x360 -900,-900,500,45,-25 "--at 1 --cloud 4 --command 0:wind:10:270:0" \
  "--at 60 --cloud 4 --command 0:wind:10:270:0"
