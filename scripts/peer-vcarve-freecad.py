# FreeCAD 0.20's Path V-carve beside swarf's vcarve (issue 40): run with `freecadcmd` by
# scripts/bench-vcarve-peers.sh, which sets the environment:
#   VP_SHAPES  a JSON file: {"rects": [[x0, y0, x1, y1], ...], "rings": [[cx, cy, r_out, r_in], ...]}
#              in the sheet's frame (mm, y up, the top at Z0); or
#   VP_DRAWING an SVG, read by FreeCAD's own importSVG, its closed wires made faces (islands
#              inside outlines, FreeCAD's "bullseye" face maker)
#   VP_OUT     where to write FreeCAD's program (its LinuxCNC post)
#   VP_ANGLE, VP_DIAMETER  the V-bit's included angle (degrees) and diameter (mm)
#   VP_DEPTH   the deepest it may go (FinalDepth, mm below the top)
#   VP_FEED    feed (mm/min)
# Each shape is a face at Z0 of one Part feature, every face given as Base geometry; FreeCAD's
# V-carve follows their medial axis (its Voronoi diagram of the discretized outline).
import json, os, sys, time

E = os.environ


def main():
    import FreeCAD, Part
    import PathScripts.PathJob as PathJob
    import PathScripts.PathStock as PathStock
    import PathScripts.PathToolBit as PathToolBit
    import PathScripts.PathToolController as PathToolController
    import PathScripts.PathVcarve as PathVcarve
    import PathScripts.PathPostProcessor as PathPostProcessor

    angle, dia, depth, feed = (float(E[k]) for k in ("VP_ANGLE", "VP_DIAMETER", "VP_DEPTH", "VP_FEED"))
    V = FreeCAD.Vector
    faces = []
    doc = FreeCAD.newDocument("vcarve")
    if E.get("VP_DRAWING"):
        import importSVG
        importSVG.insert(E["VP_DRAWING"], doc.Name)
        wires = [w for o in list(doc.Objects) if hasattr(o, "Shape") for w in o.Shape.Wires if w.isClosed()]
        for o in list(doc.Objects):
            doc.removeObject(o.Name)
        faces = Part.makeFace(wires, "Part::FaceMakerBullseye").Faces
    else:
        spec = json.load(open(E["VP_SHAPES"]))
        for x0, y0, x1, y1 in spec["rects"]:
            faces.append(Part.Face(Part.makePolygon([V(x0, y0, 0), V(x1, y0, 0), V(x1, y1, 0), V(x0, y1, 0), V(x0, y0, 0)])))
        for cx, cy, ro, ri in spec["rings"]:
            outer = Part.Wire(Part.makeCircle(ro, V(cx, cy, 0)))
            inner = Part.Wire(Part.makeCircle(ri, V(cx, cy, 0)))
            faces.append(Part.Face([outer, inner]))
    model = doc.addObject("Part::Feature", "Letters")
    model.Shape = Part.makeCompound(faces)
    doc.recompute()

    t0 = time.time()
    job = PathJob.Create("Job", [model], None)
    old = job.Stock
    job.Stock = PathStock.CreateFromBase(job, FreeCAD.Vector(0, 0, depth), FreeCAD.Vector(0, 0, 0))
    if old:
        doc.removeObject(old.Name)
    for k, v in (("ExtXneg", 0), ("ExtXpos", 0), ("ExtYneg", 0), ("ExtYpos", 0), ("ExtZneg", depth), ("ExtZpos", 0)):
        setattr(job.Stock, k, float(v))
    for extra in list(job.Tools.Group):
        doc.removeObject(extra.Name)
    bit = PathToolBit.Factory.Create("Vbit", "v-bit.fcstd")
    bit.Diameter = dia
    bit.CuttingEdgeAngle = angle
    bit.TipDiameter = 0.0
    bit.CuttingEdgeHeight = dia
    tc = PathToolController.Create("TC_vbit", tool=bit, toolNumber=1)
    job.Proxy.addToolController(tc)
    tc.VertFeed = feed / 60.0
    tc.HorizFeed = feed / 60.0
    tc.SpindleSpeed = 12000
    doc.recompute()

    op = PathVcarve.Create("Vcarve")
    op.ToolController = tc
    model_in_job = job.Model.Group[0]
    op.Base = [(model_in_job, ["Face%d" % (i + 1) for i in range(len(faces))])]
    op.setExpression("FinalDepth", None)
    op.FinalDepth = -depth
    doc.recompute()
    t1 = time.time()
    post = PathPostProcessor.PostProcessor.load("linuxcnc")
    post.export([tc, op], E["VP_OUT"], "--no-show-editor --precision 4")
    info = {"faces": len(faces), "commands": len(op.Path.Commands), "compute_s": round(t1 - t0, 3),
            "start": op.StartDepth.Value, "final": op.FinalDepth.Value}
    sys.stderr.write("VP_INFO " + json.dumps(info) + "\n")


try:
    main()
    sys.stdout.flush(); sys.stderr.flush()
    os._exit(0)
except Exception as ex:
    import traceback
    traceback.print_exc()
    sys.stderr.write("VP_ERROR %s\n" % ex)
    sys.stdout.flush(); sys.stderr.flush()
    os._exit(1)
