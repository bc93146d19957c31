#!/usr/bin/env bash
# Draws each machine's cab view at three moments of its main exercise (the scripted operator driving), side by
# side: docs/images/cab_<exercise>.png. Usage: docs/images/cab_views.sh [path/to/harboursim]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
app="${1:-$here/../../build/release/apps/harboursim/harboursim}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
shoot() {  # exercise, then three moments [s]
  local exercise="$1"; shift
  local frames=()
  for at in "$@"; do
    "$app" screenshot --exercise "$exercise" --at "$at" --view cab --size 640x360 --out "$work/$at.png" > /dev/null
    frames+=(-i "$work/$at.png")
  done
  ffmpeg -loglevel error -y "${frames[@]}" -filter_complex "hstack=inputs=$#" "$here/cab_$exercise.png"
  echo "$here/cab_$exercise.png"
}
shoot sts_discharge 12 30 75          # over the hatch cover, the box taken, landing it on the truck
shoot rtg_rehandle 20 40 90           # down the block onto the box, lifting it, over its new slot
shoot mhc_coal_discharge 20 40 60     # the grab in the hold, hoisting out, slewing to the hopper
shoot mhc_hook_lift 10 40 70          # the hook over the crate, lifting, setting it down
shoot reach_stacker_stack 10 30 60    # the box's corner: picking, carrying, landing on the stack
shoot tractor_semi_reverse 5 30 50    # over the bonnet, the mirrors and the reversing camera
shoot straddle_carrier_stack 12 40 86  # down the row to the box, lifting it, setting it on the stack
