"""Perforated panels (issue 56): a plate with n φ4 holes at an 8 mm pitch as a DXF, for n from
300 to 100,000, timed through the release CLI: reading the drawing (`swarf drawing`), profiling
every hole and the outline with a φ2 flat (4 passes, no tabs) and drilling every hole with a φ4
drill, each with the program simulated and verified as `swarf run` does. Prints one row a panel.

Usage: cargo build --release && python3 scripts/bench-panels.py [n,n,...]
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import time

SWARF = os.path.join(os.path.dirname(__file__), "..", "target", "release", "swarf")


def panel(n, path):
    cols = int(math.ceil(math.sqrt(n * 1.5)))
    rows = int(math.ceil(n / cols))
    w, h = cols * 8 + 10, rows * 8 + 10
    out = ["0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n"]
    out.append(f"0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n{w}\n20\n0\n10\n{w}\n20\n{h}\n10\n0\n20\n{h}\n")
    for k in range(n):
        out.append(f"0\nCIRCLE\n8\n0\n10\n{9 + (k % cols) * 8}\n20\n{9 + (k // cols) * 8}\n40\n2\n")
    out.append("0\nENDSEC\n0\nEOF\n")
    with open(path, "w") as f:
        f.write("".join(out))


def timed(args):
    start = time.time()
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(args)}: {r.stderr.strip()}")
    return time.time() - start


def main():
    sizes = [int(x) for x in (sys.argv[1] if len(sys.argv) > 1 else "300,1000,3000,10000,30000,100000").split(",")]
    job = json.loads(subprocess.run([SWARF, "job", "--drawing"], capture_output=True, text=True, check=True).stdout)
    job["tools"][0]["diameter"] = 2.0
    job["operations"][0]["tabs"]["count"] = 0
    profile = dict(job)
    drill = dict(job, tools=[{"number": 1, "name": "drill", "shape": "drill", "diameter": 4.0, "fluteLength": 20, "angle": 118, "spindleRpm": 3000, "feedRate": 200, "plungeRate": 100}], operations=[{"kind": "drill", "name": "drill", "tool": 1}])
    with tempfile.TemporaryDirectory() as d:
        jobs = {}
        for name, j in [("profile", profile), ("drill", drill)]:
            jobs[name] = os.path.join(d, f"{name}.json")
            with open(jobs[name], "w") as f:
                json.dump(j, f)
        print("| holes | read | profile (verified) | drill (verified) |")
        print("|---:|---:|---:|---:|")
        for n in sizes:
            dxf = os.path.join(d, f"panel{n}.dxf")
            panel(n, dxf)
            read = timed([SWARF, "drawing", dxf])
            prof = timed([SWARF, "run", jobs["profile"], dxf, "-o", os.path.join(d, "p.nc")]) if n <= 30000 else float("nan")
            dri = timed([SWARF, "run", jobs["drill"], dxf, "-o", os.path.join(d, "d.nc")])
            print(f"| {n:,} | {read:.2f} s | {prof:.1f} s | {dri:.2f} s |", flush=True)


main()
