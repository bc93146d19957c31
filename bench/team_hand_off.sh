#!/usr/bin/env bash
# The discharge gang (data/teams/sts_and_two_tractors.yaml) as three `harboursim station` processes on this
# machine, under their autopilots, RUNS times (default 3) at TIME_SCALE (default 1, real time): each run's
# hand-offs (the crane: from its first offer to the tractor's answer) and the members' states' age on arrival.
# Usage: bench/team_hand_off.sh [RUNS] [TIME_SCALE]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
app="${HARBOUR_BUILD_DIR:-$root/build/release}/apps/harboursim/harboursim"
runs="${1:-3}"
scale="${2:-1}"
roles=(crane tractor_1 tractor_2)
for run in $(seq 1 "$runs"); do
  out="$(mktemp -d)"
  for role in "${roles[@]}"; do
    "$app" station --team sts_and_two_tractors --role "$role" --autopilot --name "bench-$role" --domain 221 \
      --time-scale "$scale" --seconds 600 --window off --sound off --db "sqlite3://db=$out/$role.db" \
      > "$out/$role.log" 2>&1 &
  done
  wait || true
  echo "== run $run"
  grep -hE "handed over to|acquired from" "$out"/*.log || true
  for role in "${roles[@]}"; do
    grep -E "^  [a-z0-9_]+: [0-9]+ states" "$out/$role.log" | sed "s/^/$role /" || true
    grep -E "^loop:" "$out/$role.log" | sed "s/^/$role /" || true
  done
done
