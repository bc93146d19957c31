#!/usr/bin/env bash
# An immersive station's remote image-generator channels on this machine: `harboursim station` (sts_discharge
# under its autopilot, profile immersive_remote) and one `harboursim channel` per display named, headless at
# SIZE, for SECONDS. Prints the frames each channel showed and their rate, how far apart the channels showed
# each frame (one host: one monotonic clock), frames shown before every channel had drawn them (the swap
# lock: 0), and the station's real time.
# Usage: bench/remote_channels.sh [SECONDS] [SIZE] [DISPLAYS...]   (default: 30 640x400 left floor)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
app="${HARBOUR_BUILD_DIR:-$root/build/release}/apps/harboursim/harboursim"
seconds="${1:-30}"
size="${2:-640x400}"
shift 2 || true
displays=("$@")
[ ${#displays[@]} -eq 0 ] && displays=(left floor)
out="$(mktemp -d)"
"$app" station --exercise sts_discharge --autopilot --name bench-cabin --domain 222 --profile immersive_remote \
  --window off --sound off --seconds "$((seconds + 4))" --db "sqlite3://db=$out/records.db" > "$out/station.log" 2>&1 &
for d in "${displays[@]}"; do
  "$app" channel --station bench-cabin --display "$d" --profile immersive_remote --domain 222 --window off \
    --size "$size" --seconds "$seconds" --log "$out/$d.csv" > "$out/$d.log" 2>&1 &
done
wait || true
grep -E "^remote channels:|^loop:" "$out/station.log" || true
python3 - "$out" "${displays[@]}" <<'PY'
import csv, sys, statistics
out, displays = sys.argv[1], sys.argv[2:]
logs = {d: {int(r['frame']): r for r in csv.DictReader(open(f'{out}/{d}.csv'))} for d in displays}
for d, frames in logs.items():
    shown = sorted(int(r['shown_ns']) for r in frames.values())
    span = (shown[-1] - shown[0]) / 1e9 if len(shown) > 1 else 0
    draws = [float(r['draw_ms']) for r in frames.values()]
    print(f'{d}: {len(frames)} frames, {len(frames) / span:.1f} a second, drawing median {statistics.median(draws):.1f} ms')
first = max(min(f) for f in logs.values()) + 1
common = sorted(set.intersection(*(set(f) for f in logs.values())) - set(range(first)))
skews = sorted((max(int(logs[d][n]['shown_ns']) for d in displays) - min(int(logs[d][n]['shown_ns']) for d in displays)) / 1e6 for n in common)
early = sum(1 for n in common if min(int(logs[d][n]['shown_ns']) for d in displays) < max(int(logs[d][n]['drawn_ns']) for d in displays))
if skews:
    print(f'shown apart over {len(common)} frames: median {skews[len(skews)//2]:.2f} ms, p99 {skews[len(skews)*99//100]:.2f} ms, most {skews[-1]:.2f} ms; shown before all had drawn: {early}')
PY
