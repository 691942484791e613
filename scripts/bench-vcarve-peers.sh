#!/usr/bin/env bash
# swarf's V-carve beside FreeCAD 0.20's Path V-carve (issue 40): generated letters (two bars and
# a ring, given to both as the same shapes: a DXF for swarf, faces for FreeCAD) and the shared
# SVG drawings FreeCAD's importSVG reads. A V-bit alone (no flat tool), as deep as the letters are
# wide down to the sheet's 6 mm. Both programs measured by scripts/canon-time.py (rs274's reading,
# traverses at 3000 mm/min). See BENCHMARKS.md ("Facing, chamfering and V-carving").
# Needs FreeCAD (../shared/peers/rough/setup.sh installs it) and rs274 (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-target/vcarve-peers}
mkdir -p "$OUT"
[ -x "$(command -v freecadcmd)" ] || bash ../shared/peers/rough/setup.sh >/dev/null
cargo build --release -q
echo '{"rects": [[5, 17, 35, 27], [5, 4, 35, 14]], "rings": [[52, 15, 10, 4]]}' > "$OUT/letters.json"
python3 -c "
import json
s = json.load(open('$OUT/letters.json'))
L = ['0', 'SECTION', '2', 'ENTITIES']
for x0, y0, x1, y1 in s['rects']:
    L += ['0', 'LWPOLYLINE', '8', '0', '90', '4', '70', '1']
    for x, y in [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]:
        L += ['10', str(x), '20', str(y)]
for cx, cy, ro, ri in s['rings']:
    for r in (ro, ri):
        L += ['0', 'CIRCLE', '8', '0', '10', str(cx), '20', str(cy), '30', '0', '40', str(r)]
open('$OUT/letters.dxf', 'w').write('\n'.join(L + ['0', 'ENDSEC', '0', 'EOF']) + '\n')"
run() { # name drawing angle [freecad-source]
  local name=$1 drawing=$2 angle=$3 s e
  target/release/swarf job | python3 -c "
import json, sys
j = json.load(sys.stdin)
j['drawing'] = {'units': 'file', 'origin': 'keep', 'thickness': 6}
j['post']['rapidRate'] = 3000
j['tools'] = [{'number': 1, 'name': 'vbit', 'shape': 'vBit', 'diameter': 12, 'angle': $angle, 'tipDiameter': 0, 'fluteLength': 15, 'feedRate': 600, 'plungeRate': 600}]
j['operations'] = [{'kind': 'vcarve', 'tool': 1}]
json.dump(j, sys.stdout)" > "$OUT/$name-swarf.json"
  s=$(date +%s.%N)
  target/release/swarf run "$OUT/$name-swarf.json" "$drawing" -o "$OUT/$name-swarf.ngc" -q > "$OUT/$name-swarf.log" 2>&1
  e=$(date +%s.%N)
  echo "$name swarf: $(python3 scripts/canon-time.py "$OUT/$name-swarf.ngc") compute $(echo "$e - $s" | bc) s with verification; $(grep -c 'G0 Z' "$OUT/$name-swarf.ngc") retracts"
  env VP_OUT="$OUT/$name-freecad.ngc" VP_ANGLE=$angle VP_DIAMETER=12 VP_DEPTH=6 VP_FEED=600 "${@:4}" \
    freecadcmd scripts/peer-vcarve-freecad.py > "$OUT/$name-freecad.log" 2>&1 || { grep -a VP_ERROR "$OUT/$name-freecad.log"; return; }
  echo "$name FreeCAD: $(python3 scripts/canon-time.py "$OUT/$name-freecad.ngc") $(grep -ao 'VP_INFO.*' "$OUT/$name-freecad.log"); $(grep -c 'G0 Z' "$OUT/$name-freecad.ngc") retracts"
}
run letters "$OUT/letters.dxf" 90 VP_SHAPES="$OUT/letters.json"
for svg in pycam_polygons tm_tray-easy1; do
  f=../shared/data/profiles/$svg.svg
  [ -f "$f" ] && run "$svg" "$f" 60 VP_DRAWING="$(realpath "$f")"
done
