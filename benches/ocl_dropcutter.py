"""OpenCAMLib's BatchDropCutter on a grid, for benches/ocl_compare.rs.

usage: ocl_dropcutter.py STL X0 Y0 SPACING NX NY FLOOR SHAPE DIAMETER CORNER
(SHAPE cone: a pointed cone, CORNER its half angle in degrees)
Prints JSON: {"seconds": run time of BatchDropCutter, "threads": ..., "z": [heights row-major]}.
"""
import json
import math
import sys
import time

import opencamlib as ocl

stl, x0, y0, spacing, nx, ny, floor, shape, diameter, corner = sys.argv[1:11]
x0, y0, spacing, floor, diameter, corner = map(float, (x0, y0, spacing, floor, diameter, corner))
nx, ny = int(nx), int(ny)

surface = ocl.STLSurf()
ocl.STLReader(stl, surface)
length = 50.0
cutter = {
    "ball": lambda: ocl.BallCutter(diameter, length),
    "flat": lambda: ocl.CylCutter(diameter, length),
    "bullNose": lambda: ocl.BullCutter(diameter, corner, length),
    "cone": lambda: ocl.ConeCutter(diameter, math.radians(corner), length),
}[shape]()

started = time.perf_counter()
bdc = ocl.BatchDropCutter()
bdc.setSTL(surface)
bdc.setCutter(cutter)
for j in range(ny):
    for i in range(nx):
        bdc.appendPoint(ocl.CLPoint(x0 + i * spacing, y0 + j * spacing, floor))
bdc.run()
points = bdc.getCLPoints()
seconds = time.perf_counter() - started
threads = bdc.getThreads() if hasattr(bdc, "getThreads") else None
print(json.dumps({"seconds": seconds, "threads": threads, "z": [p.z for p in points]}))
