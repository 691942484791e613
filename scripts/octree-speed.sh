#!/usr/bin/env bash
# Issue 61's octree target: octree roughing's planning time (the φ20/12/6/3 library, verification
# off) against z-level roughing with its finest tool, the φ3, at the job's step-down (2 mm) and
# at the φ3's own octree levels (0.75 mm, seed 000's δ·D), best of three, on the shared parts, the
# generated pocket plate and the generated terrain at three sizes (scripts/terrain.mjs). Issue
# 12's settings otherwise (scripts/rough-job.sh). See BENCHMARKS.md.
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-target/octree-speed}
mkdir -p "$OUT"
cargo build --release -q
source scripts/rough-job.sh
job roughZlevel 2 3 > "$OUT/zlevel-2.json"
job roughZlevel 0.75 3 > "$OUT/zlevel-0.75.json"
job roughOctree 0 20 12 6 3 > "$OUT/octree.json"
[ -f "$OUT/pocket_plate.stl" ] || "$(bash scripts/solid-venv.sh)" scripts/pocket-plate.py "$OUT/pocket_plate.stl"
for n in 68 137 273; do [ -f "$OUT/terrain-$n.stl" ] || node scripts/terrain.mjs "$OUT/terrain-$n.stl" "$n" > /dev/null; done
best() { # job part -> the best of three planning times, or the refusal
  local t s=
  for _ in 1 2 3; do
    t=$(target/release/swarf run "$1" "$2" -o "$OUT/out.ngc" 2>&1 | grep -oE '[0-9.]+ s to compute' | cut -d' ' -f1) || { echo refused; return; }
    s=$(printf '%s\n%s\n' "$s" "$t" | grep . | sort -g | head -1)
  done
  echo "$s"
}
ratio() { [ "$2" = refused ] && echo - || echo "$1 / $2" | bc -l | xargs printf '%.1fx'; }
printf '%-18s %9s %9s %7s %9s %7s\n' part octree 'zl φ3 2' ratio 'zl φ3 .75' ratio
for part in ../shared/data/meshes/{ocl_mount_rush,kiri_pocket-test,pycam_textbox,ocl_wheel_in_box}.stl "$OUT"/pocket_plate.stl "$OUT"/terrain-{68,137,273}.stl; do
  [ -f "$part" ] || continue
  o=$(best "$OUT/octree.json" "$part"); z=$(best "$OUT/zlevel-2.json" "$part"); z7=$(best "$OUT/zlevel-0.75.json" "$part")
  printf '%-18s %9s %9s %7s %9s %7s\n' "$(basename "$part" .stl)" "$o" "$z" "$(ratio "$o" "$z")" "$z7" "$(ratio "$o" "$z7")"
done
