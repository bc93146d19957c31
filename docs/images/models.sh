#!/usr/bin/env bash
# The procedural models before and after: each view drawn with the shipped look file (after) and with a copy
# whose container, tyre, shell and hull parts are plain boxes of the same size (before), side by side:
# docs/images/models_<name>.png. Usage: docs/images/models.sh [path/to/harboursim]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
app="${1:-$here/../../build/release/apps/harboursim/harboursim}"
looks="$here/../../data/visuals"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp -r "$looks/meshes" "$work/"
# the before: every procedural shape a box (its own keys dropped), turned parts unturned
sed -E -e 's/shape: (container|tyre|shell|hull), //' -e 's/, hinge_m: [0-9.]+//' \
  -e 's/, (waterline_m: [0-9.]+|deck_open_m: \[[^]]*\]|bottom_color: \[[^]]*\]|deck_color: \[[^]]*\]|rim_color: \[[^]]*\])//g' \
  -e 's/, yaw_deg: [0-9.-]+//' -e '/,$/{N;s/,\n *turns: [^\n]*$/}/}' \
  "$looks/harbour.yaml" > "$work/boxes.yaml"
shoot() {  # name, exercise, moment [s], view, then any more screenshot options
  local name="$1" exercise="$2" at="$3" view="$4"; shift 4
  "$app" screenshot --exercise "$exercise" --at "$at" --view "$view" --size 640x360 --looks "$work/boxes.yaml" \
    --out "$work/before.png" "$@" > /dev/null
  "$app" screenshot --exercise "$exercise" --at "$at" --view "$view" --size 640x360 \
    --out "$work/after.png" "$@" > /dev/null
  ffmpeg -loglevel error -y -i "$work/before.png" -i "$work/after.png" -filter_complex hstack \
    "$here/models_$name.png"
  echo "$here/models_$name.png"
}
shoot containers_doors reach_stacker_stack 1 free --camera=-41,-3.5,1.8,25,0   # a 40 ft box's doors
shoot reach_stacker reach_stacker_stack 10 chase                                # stacks, tyres
shoot semi_trailer tractor_semi_reverse 1 chase                                 # a laden skeletal chassis
shoot rtg_cab rtg_rehandle 20 cab                                               # down between the stacks
shoot sts_cab sts_discharge 12 cab                                              # the feeder from the cab
shoot mhc_cab mhc_coal_discharge 66 cab                                         # the grab open over the hopper
