#!/usr/bin/env bash
# Issue 38's speed comparison: planning time of swarf's z-level, zigzag and octree roughing
# (verification off, the machine's cores) beside Kiri:Moto's compute time for its z-level rough
# (one thread, `../shared/peers/rough/rough_peer.sh`, the time inside the engine), on the shared
# parts and issue 61's generated pocket plate with issue 12's settings: a φ6 flat end, step-down
# 2, step-over 0.4, no allowance, the stock the part's box; octree with the φ20/12/6/3 library.
# Prints per part each program's compute time, its ratio to Kiri:Moto's, cycle time and rapids
# over feed. See BENCHMARKS.md.
# Needs ../shared beside the project; installs the peers with their setup.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
PEERS=../shared/peers/rough
OUT=${OUT:-target/rough-speed}
mkdir -p "$OUT"
bash "$PEERS/setup.sh" >/dev/null
cargo build --release -q
source scripts/rough-job.sh
job roughZlevel 2 6 > "$OUT/roughZlevel.json"
job roughZigzag 2 6 > "$OUT/roughZigzag.json"
job roughOctree 0 20 12 6 3 > "$OUT/roughOctree.json"
# Issue 61's generated pocket plate (scripts/pocket-plate.py: an exact solid by manifold3d's
# booleans, in the venv scripts/solid-venv.sh makes).
"$(bash scripts/solid-venv.sh)" scripts/pocket-plate.py "$OUT/pocket_plate.stl"
printf '%-18s %-8s %9s %9s %9s %8s\n' part program compute kiri/it cycle rapid/feed
for part in ocl_mount_rush kiri_pocket-test pycam_textbox ocl_wheel_in_box pocket_plate; do
  stl=../shared/data/meshes/$part.stl
  [ "$part" = pocket_plate ] && stl=$OUT/pocket_plate.stl
  [ -f "$stl" ] || continue
  (cd "$OUT" && "$(realpath "../../$PEERS")/rough_peer.sh" "$(realpath "../../$stl")" "$part-kiri.ngc" 6 2 0.4 > "$part-kiri.run" 2>&1)
  kiri=$(python3 -c "import json; print(json.load(open('$OUT/$part-kiri.ngc.json'))['compute_s'])")
  printf '%-18s %-8s %8.2fs\n' "$part" kiri "$kiri"
  for kind in roughZlevel roughZigzag roughOctree; do
    line=$(target/release/swarf run "$OUT/$kind.json" "$stl" -o "$OUT/$part-$kind.ngc" 2>&1 | grep "s to compute")
    compute=$(echo "$line" | sed -E 's/.*\(([0-9.]+) s to compute\).*/\1/')
    cutting=$(echo "$line" | sed -E 's/.* ([0-9]+) mm cutting.*/\1/')
    rapid=$(echo "$line" | sed -E 's/.* ([0-9]+) mm rapid.*/\1/')
    cycle=$(echo "$line" | sed -E 's/.*cycle time ([0-9:]+).*/\1/')
    printf '%-18s %-8s %8.2fs %8.1fx %9s %8.3f\n' "$part" "${kind#rough}" "$compute" "$(echo "$kiri / $compute" | bc -l)" "$cycle" "$(echo "$rapid / $cutting" | bc -l)"
  done
done
