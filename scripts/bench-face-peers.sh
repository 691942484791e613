#!/usr/bin/env bash
# swarf's facing beside Kiri:Moto 4.1.11's "level" (issue 40), on the top of a box stock: one
# level 1 mm deep over the whole stock, a φ20 flat end, step-over half the diameter, feed
# 1000 mm/min. Both programs measured by one yardstick, scripts/canon-time.py (rs274's reading,
# traverses at 3000 mm/min). Kiri's level is one pass at a depth below the stock's top: swarf's
# stock is the box with 1 mm over it, Kiri's the box, faced 1 mm down. See BENCHMARKS.md.
# Needs Kiri:Moto (../shared/peers/rough/setup.sh installs it) and rs274 (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-target/face-peers}
ENVD=${PEER_ENV:-/tmp/peer-rough-env}
mkdir -p "$OUT"
[ -d "$ENVD/kiri" ] || bash ../shared/peers/rough/setup.sh >/dev/null
cargo build --release -q
for size in "80 60" "300 200"; do
  set -- $size
  name=box-$1x$2
  python3 -c "
import struct
X, Y, Z = $1, $2, 20
c = [(x, y, z) for z in (0, Z) for y in (0, Y) for x in (0, X)]
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
tris = [t for a, b, e, d in quads for t in ((c[a], c[b], c[e]), (c[a], c[e], c[d]))]
with open('$OUT/$name.stl', 'wb') as f:
    f.write(b'\0' * 80 + struct.pack('<I', len(tris)))
    for t in tris:
        f.write(struct.pack('<3f', 0, 0, 0) + b''.join(struct.pack('<3f', *p) for p in t) + b'\0\0')"
  node scripts/peer-kiri-level.js "$ENVD/kiri" "$OUT/$name.stl" "$OUT/$name-kiri.ngc" 20 0.5 1 1000 2> "$OUT/$name-kiri.log"
  echo "$name Kiri:Moto level: $(python3 scripts/canon-time.py "$OUT/$name-kiri.ngc") $(cat "$OUT/$name-kiri.log")"
  for overlap in 0.5 0.25; do
    target/release/swarf job | python3 -c "
import json, sys
j = json.load(sys.stdin)
j['part'] = {'placement': 'keep'}
j['stock'].update({'marginXy': 0, 'marginTop': 1, 'marginBottom': 0})
j['tools'] = [{'number': 1, 'name': 'flat', 'shape': 'flat', 'diameter': 20, 'fluteLength': 30, 'feedRate': 1000, 'plungeRate': 300}]
j['operations'] = [{'kind': 'face', 'tool': 1, 'stepoverFraction': 0.5, 'stepdown': 1, 'overlap': $overlap}]
json.dump(j, sys.stdout)" > "$OUT/$name-swarf-$overlap.json"
    s=$(date +%s.%N)
    target/release/swarf run "$OUT/$name-swarf-$overlap.json" "$OUT/$name.stl" -o "$OUT/$name-swarf-$overlap.ngc" -q > "$OUT/$name-swarf-$overlap.log" 2>&1
    e=$(date +%s.%N)
    echo "$name swarf face, overlap $overlap: $(python3 scripts/canon-time.py "$OUT/$name-swarf-$overlap.ngc") compute $(echo "$e - $s" | bc) s with verification"
  done
done
