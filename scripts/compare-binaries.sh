#!/usr/bin/env bash
# Planning time of two swarf binaries, run alternately on the same jobs (a change that should
# not change speed, checked within noise), and whether their programs are byte-identical.
#   bash scripts/compare-binaries.sh OLD_SWARF NEW_SWARF [ROUNDS]
# Jobs: `swarf demo`'s (rough, raster, waterline; verified) and issue 12's z-level roughing of
# ocl_mount_rush (where ../shared/data is beside the checkout).
set -euo pipefail
old=$1 new=$2 rounds=${3:-5}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$old" demo -o "$dir/demo" > /dev/null 2>&1
mesh="$(dirname "$0")/../../shared/data/meshes/ocl_mount_rush.stl"
cat > "$dir/rough.json" <<'JSON'
{ "version": 2, "part": { "placement": "keep" }, "stock": { "marginXy": 0, "marginTop": 0, "marginBottom": 0 },
  "post": { "rapidRate": 5000 },
  "tools": [{ "number": 1, "name": "6 mm flat", "shape": "flat", "diameter": 6, "fluteLength": 60, "feedRate": 1000, "plungeRate": 250 }],
  "operations": [{ "kind": "roughZlevel", "tool": 1, "stepdown": 2, "stepoverFraction": 0.4, "allowance": 0, "leaveStock": 0, "grid": 0.25 }] }
JSON
seconds() { "$@" 2>&1 | grep -o '([0-9.]* s to compute)' | grep -o '[0-9.]*'; }
for i in $(seq "$rounds"); do
  for b in old new; do
    bin=${!b}
    d=$(seconds "$bin" run "$dir/demo/demo.json" "$dir/demo/demo.stl" -o "$dir/demo-$b.ngc")
    m=-
    [ -f "$mesh" ] && m=$(seconds "$bin" run "$dir/rough.json" "$mesh" -o "$dir/rough-$b.ngc")
    echo "round $i $b: demo $d s, mount_rush $m s"
  done
done
cmp -s "$dir/demo-old.ngc" "$dir/demo-new.ngc" && echo "demo: programs identical" || echo "demo: programs DIFFER"
[ -f "$mesh" ] && { cmp -s "$dir/rough-old.ngc" "$dir/rough-new.ngc" && echo "mount_rush: programs identical" || echo "mount_rush: programs DIFFER"; }
