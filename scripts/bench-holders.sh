#!/usr/bin/env bash
# What checking a tool's holder costs the verification (issue 58): the sample job (`swarf
# demo`: z-level rough and raster finish of the sample part) run as it is and with an ER20
# chuck on each tool, standing out far enough that nothing meets it, each three times; the
# verification stage's seconds (`--stage-times`) and their ratio.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
target/release/swarf demo -o "$dir" > /dev/null 2>&1
python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
job = json.load(open(f"{d}/demo.json"))
job["simulation"] = dict(job.get("simulation") or {}, verify=True)
json.dump(job, open(f"{d}/plain.json", "w"))
er20 = {"name": "ER20 collet chuck", "sections": [{"diameter": 34, "length": 19.5}, {"diameter": 40, "length": 40}]}
for t in job["tools"]:
    t["holder"] = er20
    t["stickOut"] = max(t.get("fluteLength", 20), 40)
json.dump(job, open(f"{d}/holder.json", "w"))
PY
verify() {
  # The stages where the moves cut the in-process stock and are judged (tool, body, holder).
  target/release/swarf run "$dir/$1.json" "$dir/demo.stl" -o "$dir/$1.ngc" -q --stage-times 2>&1 | awk '/ s  .*(in-process stock|verif|simulat)/ { s += $1 } END { printf "%.2f", s }'
}
for run in 1 2 3; do
  p=$(verify plain); h=$(verify holder)
  echo "run $run: verification $p s without holders, $h s with an ER20 on each tool: $(python3 -c "print(f'{$h / $p:.2f}')")×"
done
