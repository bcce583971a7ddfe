# FreeCAD (0.20.x) headless Path job: a plate cut out by Profile operations with the Tags
# (holding tags) dressup, and its circular holes drilled; each posted with FreeCAD's
# linuxcnc post processor.
# Run through freecad-profile (which sets the FCP_* environment variables):
#   freecadcmd /path/to/profile_job.py
#
# The plate is rebuilt from the outlines millpath reads from the drawing
# (`peer_check outlines DRAWING`, JSON: parts, windows and holes, vertices [x, y, bulge]),
# extruded from Z = -thickness to Z = 0, so both programs cut the same geometry.
#   profile.ngc  per part: a Profile of its top face's perimeter, Side Outside (the face's
#                other wires are left alone: processHoles, processCircles false), and per
#                window a Profile of its edges, Side Inside; each with a Tags dressup
#                (FCP_TABS tags, FreeCAD's default 4; Width, Height, Angle as given)
#   drill.ngc    a Drilling operation on the cylindrical faces of the holes of diameter
#                FCP_DRILL_D (G81, or G83 with FCP_PECK), with a drill of that diameter
import json
import math
import os
import time
import traceback

import FreeCAD
import Part

out = os.environ["FCP_OUT"]
OUTLINES = os.environ["FCP_OUTLINES"]
TD = float(os.environ.get("FCP_TOOL_D", 6))
THICK = float(os.environ.get("FCP_THICKNESS", 6))
DEPTH = float(os.environ.get("FCP_DEPTH", THICK))
STEPDOWN = float(os.environ.get("FCP_STEPDOWN", 2))
FEED = float(os.environ.get("FCP_FEED", 1000))  # mm/min
VFEED = float(os.environ.get("FCP_VFEED", 300))
CLEAR = float(os.environ.get("FCP_CLEARANCE", 10))  # rapids between features
SAFE = float(os.environ.get("FCP_SAFE", 2))  # where feeding down starts
TABS = os.environ.get("FCP_TABS", "")  # "" = FreeCAD's default count (4)
TAB_W = os.environ.get("FCP_TAB_WIDTH", "")  # "" = FreeCAD's default
TAB_H = os.environ.get("FCP_TAB_HEIGHT", "")
TAB_A = os.environ.get("FCP_TAB_ANGLE", "")  # 90: square; FreeCAD's default 45
DRILL_D = os.environ.get("FCP_DRILL_D", "")  # "" = no drilling
DRILL_FEED = float(os.environ.get("FCP_DRILL_FEED", 200))
DRILL_BOTTOM = float(os.environ.get("FCP_DRILL_BOTTOM", -(THICK + 1)))
DRILL_CLEAR = float(os.environ.get("FCP_DRILL_CLEARANCE", 5))
DRILL_R = float(os.environ.get("FCP_DRILL_RETRACT", 1))
PECK = float(os.environ.get("FCP_PECK", 0))

summary = {
    "params": dict(tool_d=TD, thickness=THICK, depth=DEPTH, stepdown=STEPDOWN, feed=FEED,
                   vfeed=VFEED, clearance=CLEAR, safe=SAFE, tabs=TABS, tab_width=TAB_W,
                   tab_height=TAB_H, tab_angle=TAB_A, drill_d=DRILL_D,
                   drill_feed=DRILL_FEED, drill_bottom=DRILL_BOTTOM, peck=PECK),
    "freecad_version": ".".join(FreeCAD.Version()[:3]),
    "ops": {},
    "errors": [],
}


def log(*a):
    print("[freecad_profile]", *a, flush=True)


def wire_of(vertices, z):
    """A closed wire through [x, y, bulge] vertices at height z (bulge = tan(sweep/4))."""
    edges = []
    n = len(vertices)
    for i in range(n):
        x0, y0, b = vertices[i]
        x1, y1, _ = vertices[(i + 1) % n]
        p0, p1 = FreeCAD.Vector(x0, y0, z), FreeCAD.Vector(x1, y1, z)
        if abs(b) < 1e-12:
            if (p1 - p0).Length > 1e-9:
                edges.append(Part.LineSegment(p0, p1).toShape())
            continue
        # The arc's middle point: from the chord's middle, the sagitta to the right of the
        # chord for a clockwise arc (b < 0), to the left for counter-clockwise.
        cx, cy = x1 - x0, y1 - y0
        chord = math.hypot(cx, cy)
        sag = 0.5 * chord * b  # signed: tan(theta/4) * chord / 2
        mx, my = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        nx, ny = cy / chord, -cx / chord  # right-hand normal of the chord
        mid = FreeCAD.Vector(mx + nx * sag, my + ny * sag, z)
        edges.append(Part.Arc(p0, mid, p1).toShape())
    return Part.Wire(edges)


def path_length(cmds):
    """Feed length (G1/G2/G3, arcs exact, helices included) and rapid length of a path."""
    feed = rapid = 0.0
    last = None
    for c in cmds:
        p = c.Parameters
        if c.Name not in ("G0", "G1", "G2", "G3", "G00", "G01", "G02", "G03"):
            continue
        cur = FreeCAD.Vector(p.get("X", last.x if last else 0),
                             p.get("Y", last.y if last else 0),
                             p.get("Z", last.z if last else 0))
        if last is not None:
            if c.Name in ("G0", "G00"):
                rapid += (cur - last).Length
            elif c.Name in ("G1", "G01"):
                feed += (cur - last).Length
            else:
                cx, cy = last.x + p.get("I", 0), last.y + p.get("J", 0)
                a0 = math.atan2(last.y - cy, last.x - cx)
                a1 = math.atan2(cur.y - cy, cur.x - cx)
                rr = math.hypot(last.x - cx, last.y - cy)
                da = a1 - a0
                if c.Name in ("G2", "G02"):
                    da = -((-da) % (2 * math.pi)) or -2 * math.pi
                else:
                    da = (da % (2 * math.pi)) or 2 * math.pi
                feed += math.hypot(abs(da) * rr, cur.z - last.z)
        last = cur
    return feed, rapid


try:
    import PathScripts.PathJob as PathJob
    import PathScripts.PathProfile as PathProfile
    import PathScripts.PathDrilling as PathDrilling
    import PathScripts.PathDressupHoldingTags as PathDressupTag
    import PathScripts.PathToolBit as PathToolBit
    import PathScripts.PathToolController as PathToolController
    from PathScripts.PathPostProcessor import PostProcessor

    drawing = json.load(open(OUTLINES))
    doc = FreeCAD.newDocument("profile")

    # One solid per part: its outline less its windows and holes, from -THICK up to 0.
    models = []
    for k, part in enumerate(drawing["parts"]):
        face = Part.Face(wire_of(part, -THICK))
        inner = [wire_of(w["outline"], -THICK) for w in drawing["windows"] if w["part"] == k]
        inner += [Part.Wire(Part.makeCircle(0.5 * h["d"], FreeCAD.Vector(h["x"], h["y"], -THICK)))
                  for h in drawing["holes"] if h["part"] == k]
        for w in inner:
            face = face.cut(Part.Face(w))
        solid = face.extrude(FreeCAD.Vector(0, 0, THICK))
        m = doc.addObject("Part::Feature", "Part%d" % (k + 1))
        m.Shape = solid
        models.append(m)
    doc.recompute()

    def top_face(m):
        for i, f in enumerate(m.Shape.Faces):
            bb = f.BoundBox
            if abs(bb.ZMin) < 1e-6 and abs(bb.ZMax) < 1e-6:
                return "Face%d" % (i + 1)
        raise RuntimeError("no top face on " + m.Name)

    def edges_on(m, wire):
        """The names of the model's top edges lying on `wire` (a window's outline at z=0)."""
        names = []
        for i, e in enumerate(m.Shape.Edges):
            bb = e.BoundBox
            if abs(bb.ZMin) > 1e-6 or abs(bb.ZMax) > 1e-6:
                continue
            mid = e.valueAt(0.5 * (e.FirstParameter + e.LastParameter))
            if wire.distToShape(Part.Vertex(mid))[0] < 1e-4:
                names.append("Edge%d" % (i + 1))
        return names

    job = PathJob.Create("Job", models, None)
    job.GeometryTolerance.Value = 0.01
    tc = job.Tools.Group[0]
    tc.Tool.Diameter = TD
    tc.HorizFeed = FreeCAD.Units.Quantity("%g mm/min" % FEED)
    tc.VertFeed = FreeCAD.Units.Quantity("%g mm/min" % VFEED)
    tc.SpindleSpeed = 10000
    doc.recompute()
    summary["tool"] = {"label": tc.Label, "diameter": float(tc.Tool.Diameter)}

    def heights(op, start, final, step, clear, safe):
        for p, v in (("StartDepth", start), ("FinalDepth", final), ("StepDown", step),
                     ("SafeHeight", safe), ("ClearanceHeight", clear)):
            if hasattr(op, p):
                op.setExpression(p, None)
                getattr(op, p).Value = v

    def profile_op(name, base, side, perimeter):
        op = PathProfile.Create(name)
        op.Base = base
        op.Side = side
        op.processPerimeter = perimeter
        op.processHoles = False
        op.processCircles = False
        op.ToolController = tc
        heights(op, 0.0, -DEPTH, STEPDOWN, CLEAR, SAFE)
        return op

    profiles = []
    for k, m in enumerate(models):
        profiles.append(profile_op("Profile_part%d" % (k + 1), [(m, [top_face(m)])],
                                   "Outside", True))
        windows = [w for w in drawing["windows"] if w["part"] == k]
        for j, w in enumerate(windows):
            names = edges_on(m, wire_of(w["outline"], 0.0))
            profiles.append(profile_op("Profile_part%d_window%d" % (k + 1, j + 1),
                                       [(m, names)], "Inside", False))
    t0 = time.perf_counter()
    doc.recompute()
    t_profile = time.perf_counter() - t0

    dressed = []
    t0 = time.perf_counter()
    for op in profiles:
        d = PathDressupTag.Create(op, "Tags_" + op.Name)
        if TAB_W:
            d.Width = float(TAB_W)
        if TAB_H:
            d.Height = float(TAB_H)
        if TAB_A:
            d.Angle = float(TAB_A)
        d.Proxy.generateTags(d, int(TABS) if TABS else 4)
        doc.recompute()
        placed = len(d.Positions) - len(d.Disabled)
        summary["ops"]["tags_" + op.Name] = {"asked": int(TABS) if TABS else 4,
                                             "placed": placed,
                                             "width": float(d.Width), "height": float(d.Height),
                                             "angle": float(d.Angle)}
        log("%s: %d tags placed, width %.3f, height %.3f, angle %.1f"
            % (op.Name, placed, float(d.Width), float(d.Height), float(d.Angle)))
        dressed.append(d)
    t_tags = time.perf_counter() - t0

    post = PostProcessor.load("linuxcnc")
    cmds = [c for d in dressed for c in d.Path.Commands]
    feed, rapid = path_length(cmds)
    fn = os.path.join(out, "profile.ngc")
    post.export([tc] + dressed, fn, "--no-show-editor --precision 4")
    summary["ops"]["profile"] = {"generation_s": t_profile + t_tags, "commands": len(cmds),
                                 "feed_length_mm": feed, "rapid_length_mm": rapid, "file": fn}
    log("profile: %d operations, generated in %.3f s (tags %.3f s), %d commands, feed %.1f mm,"
        " rapid %.1f mm -> %s" % (len(dressed), t_profile + t_tags, t_tags, len(cmds), feed,
                                  rapid, fn))

    if DRILL_D:
        dd = float(DRILL_D)
        bit = PathToolBit.Factory.CreateFrom(PathToolBit.findToolBit("5mm_Drill.fctb"), "Drill")
        bit.Diameter = dd
        dtc = PathToolController.Create("TC_Drill", bit, 2)
        dtc.VertFeed = FreeCAD.Units.Quantity("%g mm/min" % DRILL_FEED)
        dtc.HorizFeed = FreeCAD.Units.Quantity("%g mm/min" % FEED)
        dtc.SpindleSpeed = 10000
        job.Proxy.addToolController(dtc)
        base = []
        count = 0
        for m in models:
            subs = []
            for i, f in enumerate(m.Shape.Faces):
                s = f.Surface
                if isinstance(s, Part.Cylinder) and abs(s.Radius - 0.5 * dd) < 0.005:
                    subs.append("Face%d" % (i + 1))
            if subs:
                base.append((m, subs))
                count += len(subs)
        op = PathDrilling.Create("Drilling")
        op.Base = base
        op.ToolController = dtc
        op.ReturnLevel = "G98"
        op.ExtraOffset = "None"
        op.PeckEnabled = PECK > 0
        if PECK > 0:
            op.setExpression("PeckDepth", None)
            op.PeckDepth = PECK
        op.setExpression("RetractHeight", None)
        op.RetractHeight = DRILL_R
        heights(op, 0.0, DRILL_BOTTOM, 1.0, DRILL_CLEAR, DRILL_R)
        t0 = time.perf_counter()
        doc.recompute()
        dt = time.perf_counter() - t0
        cmds = op.Path.Commands
        feed, rapid = path_length(cmds)
        fn = os.path.join(out, "drill.ngc")
        post.export([dtc, op], fn, "--no-show-editor --precision 4")
        summary["ops"]["drill"] = {"generation_s": dt, "holes": count, "commands": len(cmds),
                                   "feed_length_mm": feed, "rapid_length_mm": rapid, "file": fn}
        log("drill: %d holes of %.3f mm, generated in %.3f s, %d commands -> %s"
            % (count, dd, dt, len(cmds), fn))
    try:
        doc.saveAs(os.path.join(out, "profile_job.FCStd"))
    except Exception as ex:
        summary["errors"].append("save FCStd failed: %r" % ex)
except Exception as ex:
    summary["errors"].append(repr(ex))
    summary["traceback"] = traceback.format_exc()
    log("ERROR", repr(ex))
    traceback.print_exc()

with open(os.path.join(out, "summary.json"), "w") as f:
    json.dump(summary, f, indent=1)
