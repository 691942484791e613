#!/usr/bin/env bash
# Seed 004's zigzag roughing side by side with FreeCAD 0.20's Adaptive (../shared/peers/rough/)
# on the shared pocket test and the paper-like pocket: cycle time and material left by the
# peers' own checker (gcode_stats.py), the removal rate per 1.2 mm of level cutting by swarf's
# simulation (`cargo bench --bench zigzag -- load`), and compute time. See BENCHMARKS.md.
# Needs ../shared beside the project; installs the peers with their setup.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
PEERS=../shared/peers/rough
OUT=${OUT:-target/zigzag-peers}
mkdir -p "$OUT"
bash "$PEERS/setup.sh" >/dev/null
cargo build --release -q
cargo bench --bench zigzag -q >/dev/null   # writes target/paper_pocket.stl
# The pocket test with issue 12's settings (φ6 flat, step-down 2, step-over 0.4); the paper's
# pocket with its own (φ10 flat, axial 0.5, radial 3 mm).
run() { # name stl diameter stepdown stepover
  local name=$1 stl=$2 d=$3 sd=$4 so=$5
  for load in path feed none; do
    target/release/swarf job | python3 -c "
import json, sys
j = json.load(sys.stdin)
j['part'] = {'placement': 'keep'}
j['stock'].update({'marginXy': 0, 'marginTop': 0, 'marginBottom': 0})
j['post']['rapidRate'] = 5000
j['tools'] = [{'number': 1, 'name': 'flat', 'shape': 'flat', 'diameter': $d, 'fluteLength': 50, 'feedRate': 1000, 'plungeRate': 250}]
j['operations'] = [{'kind': 'roughZigzag', 'tool': 1, 'stepdown': $sd, 'stepover': $so, 'allowance': 0, 'leaveStock': 0, 'load': '$load', 'grid': 0.5}]
json.dump(j, sys.stdout)" > "$OUT/$name-$load.json"
    local s e
    s=$(date +%s.%N)
    target/release/swarf run "$OUT/$name-$load.json" "$stl" -o "$OUT/$name-swarf-$load.ngc" -q > "$OUT/$name-swarf-$load.log" 2>&1
    e=$(date +%s.%N)
    echo "$name swarf ($load): compute $(echo "$e - $s" | bc) s (with its own verification)"
  done
  s=$(date +%s.%N)
  (cd "$OUT" && PEER=freecad-adaptive timeout 1800 "$(realpath "../../$PEERS")/rough_peer.sh" "$(realpath "../../$stl")" "$name-freecad-adaptive.ngc" "$d" "$sd" "$so" > "$name-freecad-adaptive.run" 2>&1) || true
  e=$(date +%s.%N)
  echo "$name FreeCAD Adaptive: wall $(echo "$e - $s" | bc) s"
  for p in "$OUT/$name"-swarf-*.ngc "$OUT/$name-freecad-adaptive.ngc"; do
    [ -s "$p" ] || continue
    /usr/bin/python3 "$PEERS/gcode_stats.py" "$p" --stl "$stl" --tool "$d" --rapid 5000 --json | python3 -c "
import json, sys
s = json.load(sys.stdin)
print('$p', 'feed', s['length_mm']['feed'], 'mm; est', s['time_est_min']['total'], 'min; left', s['sim']['material_left_mm3'], 'mm3; gouges', s['sim']['gouge_cells'])"
  done
  cargo bench -q --bench zigzag -- load "$d" "$stl" "$OUT/$name"-swarf-*.ngc $( [ -s "$OUT/$name-freecad-adaptive.ngc" ] && echo "$OUT/$name-freecad-adaptive.ngc" )
}
run pocket-test ../shared/data/meshes/kiri_pocket-test.stl 6 2 0.4
run paper-pocket target/paper_pocket.stl 10 0.5 0.3
