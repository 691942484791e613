#!/usr/bin/env bash
# Adaptive clearing (issue 59) side by side with FreeCAD 0.20's Adaptive (../shared/peers/rough/,
# PEER=freecad-adaptive) on the shared pocket test: the same φ6 flat, step-down, optimal load,
# feed (1000 mm/min) and stock (the part's box). Moves, cycle time and material left by the
# peers' own checker (gcode_stats.py, rapids at 5000 mm/min), the engagement along the cut by
# swarf's simulation (`cargo bench --bench zigzag -- engagement`), and compute time.
# Needs ../shared beside the project; installs the peers with their setup.sh. See BENCHMARKS.md.
set -euo pipefail
cd "$(dirname "$0")/.."
PEERS=../shared/peers/rough
OUT=${OUT:-target/adaptive-peers}
mkdir -p "$OUT"
bash "$PEERS/setup.sh" >/dev/null
cargo build --release -q
run() { # name stl diameter stepdown load
  local name=$1 stl=$2 d=$3 sd=$4 so=$5 s e
  target/release/swarf job | python3 -c "
import json, sys
j = json.load(sys.stdin)
j['part'] = {'placement': 'keep'}
j['stock'].update({'marginXy': 0, 'marginTop': 0, 'marginBottom': 0})
j['post']['rapidRate'] = 5000
j['tools'] = [{'number': 1, 'name': 'flat', 'shape': 'flat', 'diameter': $d, 'fluteLength': 50, 'feedRate': 1000, 'plungeRate': 250}]
j['operations'] = [{'kind': 'roughAdaptive', 'tool': 1, 'stepdown': $sd, 'stepoverFraction': $so, 'allowance': 0, 'leaveStock': 0, 'grid': 0.5}]
json.dump(j, sys.stdout)" > "$OUT/$name.json"
  s=$(date +%s.%N)
  target/release/swarf run "$OUT/$name.json" "$stl" -o "$OUT/$name-swarf.ngc" --stage-times > "$OUT/$name-swarf.log" 2>&1
  e=$(date +%s.%N)
  echo "$name swarf: wall $(echo "$e - $s" | bc) s with its own verification; planning: $(grep -E 'adaptive rough: (rings|levels|CL)' "$OUT/$name-swarf.log" | awk '{s += $1} END {print s}') s"
  s=$(date +%s.%N)
  (cd "$OUT" && PEER=freecad-adaptive timeout 1800 "$(realpath "../../$PEERS")/rough_peer.sh" "$(realpath "../../$stl")" "$name-freecad.ngc" "$d" "$sd" "$so" > "$name-freecad.run" 2>&1) || true
  e=$(date +%s.%N)
  echo "$name FreeCAD Adaptive: wall $(echo "$e - $s" | bc) s; inside the peer $(python3 -c "import json; print(json.load(open('$OUT/$name-freecad.ngc.json'))['compute_s'])" 2>/dev/null || echo '?') s"
  for p in "$OUT/$name-swarf.ngc" "$OUT/$name-freecad.ngc"; do
    [ -s "$p" ] || continue
    /usr/bin/python3 "$PEERS/gcode_stats.py" "$p" --stl "$stl" --tool "$d" --rapid 5000 --json | python3 -c "
import json, sys
s = json.load(sys.stdin)
print('$p', 'moves', s['moves_total'], '; feed', s['length_mm']['feed'], 'mm; est', s['time_est_min']['total'], 'min; left', s['sim']['material_left_mm3'], 'mm3; gouges', s['sim']['gouge_cells'])"
  done
  cargo bench -q --bench zigzag -- engagement "$d" "$sd" "$(echo "$so * $d" | bc -l)" 1000 "$stl" "$OUT/$name-swarf.ngc" $( [ -s "$OUT/$name-freecad.ngc" ] && echo "$OUT/$name-freecad.ngc" )
}
run pocket-test-0.4 ../shared/data/meshes/kiri_pocket-test.stl 6 2 0.4
run pocket-test-0.1 ../shared/data/meshes/kiri_pocket-test.stl 6 8 0.1
