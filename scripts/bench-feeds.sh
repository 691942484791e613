#!/usr/bin/env bash
# Issue 58's feed optimisation on the shared roughing parts: each part roughed by z-level with
# a φ6 flat end (step-down 2, step-over 0.4, feed 1000, rapids and air feed 5000, the stock the
# part's box, as `scripts/rough-speed.sh`), once at the feeds as planned and once with
# `simulation.optimizeFeeds`; prints both cycle times, their ratio, what the optimisation did
# and the thickest chip the simulation measured against the tool's chip load, and verifies the
# optimised program read back from its G-code (`swarf verify`). See BENCHMARKS.md.
# Needs ../shared beside the project.
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-target/bench-feeds}
mkdir -p "$OUT"
cargo build --release -q
job() { # optimise (true/false) -> job json
  target/release/swarf job | python3 -c "
import json, sys
j = json.load(sys.stdin)
j['part'] = {'placement': 'keep'}
j['stock'].update({'marginXy': 0, 'marginTop': 0, 'marginBottom': 0})
j['post']['rapidRate'] = 5000
j['simulation']['optimizeFeeds'] = $1
j['tools'] = [{'number': 1, 'name': 'f6', 'shape': 'flat', 'diameter': 6, 'fluteLength': 50, 'flutes': 2, 'spindleRpm': 10000, 'feedRate': 1000, 'plungeRate': 250}]
j['operations'] = [{'kind': 'roughZlevel', 'tool': 1, 'stepdown': 2, 'stepoverFraction': 0.4, 'allowance': 0, 'leaveStock': 0, 'grid': 0.5}]
json.dump(j, sys.stdout)"
}
job False > "$OUT/plain.json"
job True > "$OUT/optimised.json"
printf '%-18s %9s %9s %6s %8s %7s %12s %9s\n' part plain optimised ratio faster air chip/limit verify
for part in ocl_mount_rush kiri_pocket-test pycam_textbox ocl_wheel_in_box; do
  stl=../shared/data/meshes/$part.stl
  [ -f "$stl" ] || continue
  cycle() { grep -o 'cycle time [0-9:]*' "$1" | head -1 | awk '{print $3}'; }
  # A program its simulation refuses is said so, not timed.
  if ! target/release/swarf run "$OUT/plain.json" "$stl" -o "$OUT/$part-plain.ngc" > "$OUT/$part-plain.log" 2>&1 ||
     ! target/release/swarf run "$OUT/optimised.json" "$stl" -o "$OUT/$part-optimised.ngc" > "$OUT/$part-optimised.log" 2>&1; then
    printf '%-18s refused: %s\n' "$part" "$(grep -h '^swarf:' "$OUT/$part-plain.log" "$OUT/$part-optimised.log" 2>/dev/null | head -1)"
    continue
  fi
  secs() { echo "$1" | awk -F: '{s=0; for (i=1;i<=NF;i++) s=s*60+$i; print s}'; }
  a=$(cycle "$OUT/$part-plain.log"); b=$(cycle "$OUT/$part-optimised.log")
  line=$(grep 'feeds optimised' "$OUT/$part-optimised.log")
  faster=$(echo "$line" | sed -E 's/feeds optimised: ([0-9]+) cuts.*/\1/')
  air=$(echo "$line" | sed -E 's/.*, ([0-9]+) moves in air.*/\1/')
  chip=$(grep -o 'thickest chip [0-9.]*' "$OUT/$part-optimised.log" | awk '{print $3}' | sort -g | tail -1)
  if target/release/swarf verify "$OUT/optimised.json" "$stl" "$OUT/$part-optimised.ngc" > "$OUT/$part-verify.log" 2>&1; then ok=clean; else ok=FAILED; fi
  printf '%-18s %9s %9s %6.3f %8s %7s %5s/%-6s %9s\n' "$part" "$a" "$b" "$(echo "$(secs "$b") / $(secs "$a")" | bc -l)" "$faster" "$air" "${chip:-?}" 0.05 "$ok"
done
