#!/usr/bin/env bash
# Eight `harboursim station` processes in one team session on this machine, each under its autopilot for
# SECONDS (default 60) of wall time: each prints its loop's real-time factor, late and given-up ticks, and the
# other members' states' age on arrival. Usage: bench/team_of_eight.sh [SECONDS]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
app="${HARBOUR_BUILD_DIR:-$root/build/release}/apps/harboursim/harboursim"
seconds="${1:-60}"
out="$(mktemp -d)"
roles=(sts-1 sts-2 rtg mhc stacker tractor-1 tractor-2 tractor-3)
for role in "${roles[@]}"; do
  "$app" station --team "$root/bench/data/teams/eight.yaml" --role "$role" --autopilot --name "bench-$role" \
    --domain 219 --seconds "$seconds" --window off --sound off --db "sqlite3://db=$out/$role.db" \
    > "$out/$role.log" 2>&1 &
done
wait || true
for role in "${roles[@]}"; do
  echo "== $role"
  grep -E "^loop:|^team eight|^  [a-z0-9-]+: [0-9]+ states|^stored as" "$out/$role.log" || tail -5 "$out/$role.log"
done
