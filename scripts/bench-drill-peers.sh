#!/usr/bin/env bash
# swarf's drilling beside FreeCAD 0.20's Path Drilling (issue 39) on the same holes: a plate built
# by FreeCAD as a solid (tests its own hole finding on the BRep) and written as an STL for swarf
# (which finds the holes in the triangles). Both programs are measured by one yardstick,
# scripts/canon-time.py: LinuxCNC's rs274 expands every canned cycle, feed moves at their feed,
# traverses at 3000 mm/min for both. See BENCHMARKS.md ("Drilling beside FreeCAD").
# Needs FreeCAD (../shared/peers/rough/setup.sh installs it) and rs274 (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-target/drill-peers}
mkdir -p "$OUT"
[ -x "$(command -v freecadcmd)" ] || bash ../shared/peers/rough/setup.sh >/dev/null
cargo build --release -q
case_() { # name count diameter plate_x plate_y thickness spacing drill peck
  local name=$1 n=$2 hd=$3 px=$4 py=$5 pt=$6 gap=$7 d=$8 peck=$9
  python3 -c "
import json, random
r = random.Random(39)
holes = []
while len(holes) < $n:
    x, y = r.uniform(8, $px - 8), r.uniform(8, $py - 8)
    if all((x - a) ** 2 + (y - b) ** 2 > $gap ** 2 for a, b, _ in holes):
        holes.append([round(x, 3), round(y, 3), $hd])
json.dump({'plate': [$px, $py, $pt], 'holes': holes}, open('$OUT/$name.json', 'w'))"
  local s e
  s=$(date +%s.%N)
  DP_HOLES=$OUT/$name.json DP_STL=$OUT/$name.stl DP_OUT=$OUT/$name-freecad.ngc DP_DRILL=$d DP_ANGLE=118 \
    DP_PECK=$peck DP_RETRACT=1 DP_PLUNGE=150 freecadcmd scripts/peer-drill-freecad.py > "$OUT/$name-freecad.log" 2>&1 \
    || { grep DP_ERROR "$OUT/$name-freecad.log"; exit 1; }
  e=$(date +%s.%N)
  echo "$name: FreeCAD $(grep -o 'DP_INFO.*' "$OUT/$name-freecad.log") (wall $(echo "$e - $s" | bc) s with the plate and its STL)"
  local cycle=drill; [ "$peck" = 0 ] || cycle=peck
  target/release/swarf job | python3 -c "
import json, sys
j = json.load(sys.stdin)
j['part'] = {'placement': 'keep'}
j['stock'].update({'marginXy': 0, 'marginTop': 0, 'marginBottom': 0, 'clearance': 3})
j['post']['rapidRate'] = 3000
j['tools'] = [{'number': 1, 'name': 'drill', 'shape': 'drill', 'diameter': $d, 'angle': 118, 'fluteLength': 40, 'feedRate': 150, 'plungeRate': 150, 'spindleRpm': 2000}]
j['operations'] = [{'kind': 'drill', 'tool': 1, 'cycle': '$cycle', 'peck': max($peck, 0.1), 'retract': 1, 'breakthrough': 0}]
json.dump(j, sys.stdout)" > "$OUT/$name-swarf.json"
  s=$(date +%s.%N)
  target/release/swarf run "$OUT/$name-swarf.json" "$OUT/$name.stl" -o "$OUT/$name-swarf.ngc" -q > "$OUT/$name-swarf.log" 2>&1
  e=$(date +%s.%N)
  echo "$name: swarf $(grep -c 'G8[13]' "$OUT/$name-swarf.ngc") holes, compute $(echo "$e - $s" | bc) s (reading the STL, finding the holes, planning, verifying)"
  for p in swarf freecad; do
    echo "$name $p: $(python3 scripts/canon-time.py "$OUT/$name-$p.ngc" --rapid 3000)"
  done
}
# name    holes  ø   plate       t   gap  drill peck
case_ peck30   30   6   150 100    12  15   6     3
case_ g81-120  120  3.3 200 150    6   9    3.3   0
