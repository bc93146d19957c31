#!/usr/bin/env bash
# The cab's sound of four exercises, the scripted operator driving, as spectrograms of its left channel
# (sox): docs/images/sound_<exercise>.png. Usage: docs/images/sound_spectrograms.sh [path/to/harboursim]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
app="${1:-$here/../../build/release/apps/harboursim/harboursim}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
listen() {  # exercise, seconds heard, the band shown [Hz] (twice it: the rate sox resamples to), title
  local exercise="$1" seconds="$2" rate="$3" title="$4"
  "$app" run --exercise "$exercise" --autopilot --db "sqlite3://db=$work/records.db" --record "$work/$exercise.hsrc" \
    > /dev/null
  "$app" render "$work/$exercise.hsrc" --exercise "$exercise" --audio "$work/$exercise.wav" --to "$seconds" > /dev/null
  sox "$work/$exercise.wav" -n remix 1 rate "$rate" spectrogram -x 900 -y 257 -z 80 -t "$exercise (autopilot): $title" \
    -o "$here/sound_$exercise.png"
  echo "$here/sound_$exercise.png"
}
listen sts_discharge 88 2k "hoist and trolley motors, brake and twistlock clunks, landings"
listen mhc_coal_discharge 90 8k "winches, slewing, the engine's turbo, coal pouring at 62 s"
listen tractor_mafi_park 53 4k "the diesel's firing harmonics through its gears"
listen straddle_carrier_stack 90 4k "its generator set's firing, the hoist motors, the twistlocks, the reversing beeper"
