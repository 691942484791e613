#!/usr/bin/env python3
"""A program's machine time from LinuxCNC's own reading of it (`rs274 -g`'s canon), for comparing
programs of different CAMs with one measure: every canned cycle as rs274 expands it, feed moves (lines and
XY arcs, helices too) at their feed rate, traverses at the given rapid rate, dwells as written; tool changes and
acceleration are left out. The tool starts where the program first sends it.

    canon-time.py PROGRAM.ngc [--rapid 3000]   -> prints JSON: time_s, feed_mm, rapid_mm, dwell_s, moves
"""
import json, math, re, subprocess, sys

args = sys.argv[1:]
rapid = 3000.0
if "--rapid" in args:
    i = args.index("--rapid")
    rapid = float(args[i + 1])
    del args[i:i + 2]
out = subprocess.run(["rs274", "-g", args[0]], stdin=subprocess.DEVNULL, capture_output=True, text=True)
if out.returncode != 0:
    sys.exit("rs274 refused %s: %s" % (args[0], out.stdout[-400:] + out.stderr[-400:]))
num = r"(-?\d+(?:\.\d+)?)"
move = re.compile(r"(STRAIGHT_TRAVERSE|STRAIGHT_FEED)\(" + ",\s*".join([num] * 3))
arc = re.compile(r"ARC_FEED\(" + ",\s*".join([num] * 6))
feed, at = None, None
t = feed_mm = rapid_mm = dwell = 0.0
moves = 0
for line in out.stdout.splitlines():
    m = move.search(line)
    if m:
        p = tuple(float(v) for v in m.groups()[1:4])
        if at is not None:
            d = math.dist(at, p)
            if m.group(1) == "STRAIGHT_TRAVERSE":
                rapid_mm += d
                t += d / rapid * 60
            else:
                feed_mm += d
                t += d / feed * 60
        at = p
        moves += 1
    elif arc.search(line):
        # XY arcs (G17): end X Y, centre X Y, turns (+ counter-clockwise), end Z.
        ex, ey, cx, cy, turns, ez = (float(v) for v in arc.search(line).groups())
        r = math.hypot(at[0] - cx, at[1] - cy)
        a0, a1 = math.atan2(at[1] - cy, at[0] - cx), math.atan2(ey - cy, ex - cx)
        sweep = (a1 - a0) % (2 * math.pi) if turns > 0 else (a0 - a1) % (2 * math.pi)
        if sweep < 1e-12:
            sweep = 2 * math.pi
        sweep += 2 * math.pi * (abs(turns) - 1)
        d = math.hypot(r * sweep, ez - at[2])
        feed_mm += d
        t += d / feed * 60
        at = (ex, ey, ez)
        moves += 1
    elif "SET_FEED_RATE(" in line:
        feed = float(line.split("SET_FEED_RATE(")[1].split(")")[0])
    elif "DWELL(" in line:
        s = float(line.split("DWELL(")[1].split(")")[0])
        dwell += s
        t += s
print(json.dumps({"time_s": round(t, 1), "feed_mm": round(feed_mm, 1), "rapid_mm": round(rapid_mm, 1), "dwell_s": dwell, "moves": moves}))
