#!/usr/bin/env bash
# The machines before and after their parts were drawn as built: each view drawn with the machine files of an
# earlier commit (before: its data, through the exercise's own files) and with the shipped ones (after), side
# by side: docs/images/machines_<name>.png. Usage: docs/images/machines.sh [before-commit] [path/to/harboursim]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
before="${1:-ead6600}"
app="${2:-$here/../../build/release/apps/harboursim/harboursim}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
git -C "$here/../.." archive "$before" data | tar -x -C "$work"
shoot() {  # name, exercise, moment [s], view, then any more screenshot options
  local name="$1" exercise="$2" at="$3" view="$4"; shift 4
  "$app" screenshot --exercise "$work/data/exercises/$exercise.yaml" --at "$at" --view "$view" --size 640x360 \
    --out "$work/before.png" "$@" > /dev/null
  "$app" screenshot --exercise "$exercise" --at "$at" --view "$view" --size 640x360 \
    --out "$work/after.png" "$@" > /dev/null
  ffmpeg -loglevel error -y -i "$work/before.png" -i "$work/after.png" -filter_complex hstack \
    "$here/machines_$name.png"
  echo "$here/machines_$name.png"
}
shoot sts_spreader sts_discharge 2 free --camera=25,-9,23,51,-18       # spreader and headblock
shoot sts_cab sts_discharge 5 cab                                      # the spreader from the cab
shoot sts_trolley sts_discharge 1 free --camera=20,-22,44,50,4         # trolley and cab from below
shoot reach_stacker reach_stacker_stack 0.5 free --camera=-18,-28,3,160,-5
shoot reach_stacker_cab reach_stacker_stack 3 cab
shoot straddle_carrier straddle_carrier_stack 0.2 free --camera=-26,-8,4,150,8
shoot straddle_carrier_cab straddle_carrier_stack 3 cab
shoot mhc_house mhc_coal_discharge 1 free --camera=-14,12,14,-31,-12    # house, counterweight, tower
shoot tractor tractor_semi_reverse 0.5 free --camera=-52,8,3,-135,-8   # the tractor from ahead
shoot sts_reel sts_discharge 1 free --camera=-30,-30,4,60,5            # legs, cable reel, stairs
shoot bulk_carrier_house mhc_coal_discharge 1 free --camera=5,-55,22,-40,0   # the bulk carrier's house
