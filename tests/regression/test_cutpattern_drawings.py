"""Cutting-pattern drawings a cutting table takes, the roll nesting and the fabrication-error
report (docs/fabrication.md). Three strips (cylinder and cone: developable; a sphere strip:
doubly curved; pattern_meshes.py) are cut with a 15 mm seam allowance and nested on a roll; the
DXF files are read back with ezdxf (python3-ezdxf, in scripts/setup):
  * the header declares mm ($INSUNITS 4, ezdxf's doc.units) and metric ($MEASUREMENT 1);
  * each outline is one closed polyline (no LINE segments) on its layer: OUTLINE (the cut line,
    15 mm outside), WELD (the net pattern edge), an MD arrow, labels on TEXT;
  * the labels give the strip's name, its length and width (the WELD outline's box), each edge's
    arc length and the two diagonals, equal to the outline measured here to 0.1 mm;
  * no text box (one text height per character, as etfe/analyses/pattern_sheet.h) crosses an outline or
    leaves the sheet ($EXTMIN/$EXTMAX);
  * nesting: every strip within the roll's width, no two overlapping, the roll length and the
    waste printed and equal to what the nesting DXF's outlines give; a roll narrower than a
    strip is refused naming the strip and its width;
  * errors CSV: the developable strips' length and area errors below 1e-6, the sphere strip's
    interior error and area strain reported and not small; above the first-yield strain (here
    a low -material_yield) a warning names the strip."""
import csv
import math
import os
import re

import pattern_meshes as pm
from etfe_testlib import Checker, etfe_path, run, scratch_dir

try:
    import ezdxf
except ImportError:  # the check below fails with the way out
    ezdxf = None

etfe = etfe_path()
chk = Checker("cutpattern_drawings")
ROLL, GAP, ALLOW = 1100.0, 10.0, 15.0


def polylines(doc, layer):
    return [e for e in doc.modelspace() if e.dxftype() in ("POLYLINE", "LWPOLYLINE") and e.dxf.layer == layer]


def points(e):
    return [(p[0], p[1]) for p in (e.points() if e.dxftype() == "POLYLINE" else e.get_points("xy"))]


def area(p):
    return 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(p, p[1:] + p[:1]))


def corners(p, min_turn=30.0):
    """Indices of the vertices where the closed outline turns by more than min_turn degrees."""
    out = []
    n = len(p)
    for k in range(n):
        a, q, b = p[k - 1], p[k], p[(k + 1) % n]
        t = math.degrees(abs(math.atan2(b[1] - q[1], b[0] - q[0]) - math.atan2(q[1] - a[1], q[0] - a[0])))
        if min(t, 360 - t) > min_turn:
            out.append(k)
    return out


def seg_meets_box(a, b, box):
    """Liang-Barsky: does the segment a-b meet box (x0, y0, x1, y1)?"""
    t0, t1 = 0.0, 1.0
    for k in range(2):
        d = b[k] - a[k]
        lo, hi = box[k], box[k + 2]
        if abs(d) < 1e-300:
            if a[k] < lo or a[k] > hi:
                return False
            continue
        ta, tb = sorted(((lo - a[k]) / d, (hi - a[k]) / d))
        t0, t1 = max(t0, ta), min(t1, tb)
        if t0 > t1:
            return False
    return True


def text_box(t):
    h, (x, y) = t.dxf.height, (t.dxf.insert[0], t.dxf.insert[1])
    return (x, y - 0.35 * h, x + h * len(t.dxf.text), y + 1.2 * h)


def number(texts, prefix):
    for t in texts:
        m = re.match(re.escape(prefix) + r" ([-\d.]+)", t)
        if m:
            return float(m.group(1))
    return float("nan")


def check_strip(tmp, name):
    path = os.path.join(tmp, "strips_%s.dxf" % name)
    doc = ezdxf.readfile(path)
    chk.check(doc.units == 4 and doc.header.get("$INSUNITS") == 4 and doc.header.get("$MEASUREMENT") == 1,
              "%s: the DXF header declares mm ($INSUNITS %s, ezdxf units %s) and metric ($MEASUREMENT %s)"
              % (name, doc.header.get("$INSUNITS"), doc.units, doc.header.get("$MEASUREMENT")))
    layers = {l.dxf.name for l in doc.layers}
    chk.check({"OUTLINE", "WELD", "MD", "TEXT"} <= layers, "%s: layers OUTLINE, WELD, MD, TEXT (%s)"
              % (name, ", ".join(sorted(layers))))
    kinds = {e.dxftype() for e in doc.modelspace()}
    cut, weld = polylines(doc, "OUTLINE"), polylines(doc, "WELD")
    chk.check("LINE" not in kinds and len(cut) == 1 and len(weld) == 1 and all(e.is_closed for e in cut + weld),
              "%s: one closed polyline on OUTLINE and on WELD, no LINE segments (%s)" % (name, sorted(kinds)))
    chk.check(len(polylines(doc, "MD")) >= 1, "%s: the MD arrow on layer MD" % name)
    if not cut:
        return
    c, w = points(cut[0]), points((weld or cut)[0])
    # The cut line lies the allowance outside the weld line: its area grows by about the
    # perimeter times the allowance.
    perim = sum(math.dist(a, b) for a, b in zip(w, w[1:] + w[:1]))
    grow = (abs(area(c)) - abs(area(w))) / (perim * ALLOW)
    chk.check(0.95 < grow < 1.1, "%s: OUTLINE is the cut line %g mm outside WELD (area grows %.3f x perimeter x "
              "allowance)" % (name, ALLOW, grow))
    texts = [e for e in doc.modelspace() if e.dxftype() == "TEXT"]
    labels = [t.dxf.text for t in texts if t.dxf.layer == "TEXT"]
    chk.check(any(t.startswith(name + " ") for t in labels), "%s: the strip's name is a label" % name)
    if name == "cylinder":
        chk.check(any(t.startswith("weld_bottom ") for t in labels) and "WELD_BOTTOM" in layers,
                  "cylinder: the named line weld_bottom on its layer, its length a label")
    xs, ys = [p[0] for p in w], [p[1] for p in w]
    m = [re.match(r"length ([\d.]+) x width ([\d.]+)", t) for t in labels]
    m = [x for x in m if x]
    L, W = (float(m[0].group(1)), float(m[0].group(2))) if m else (math.nan, math.nan)
    chk.check(abs(L - (max(xs) - min(xs))) <= 0.051 and abs(W - (max(ys) - min(ys))) <= 0.051,
              "%s: length x width printed %.1f x %.1f = the weld outline's box %.3f x %.3f"
              % (name, L, W, max(xs) - min(xs), max(ys) - min(ys)))
    cs = corners(w)
    chk.check(len(cs) == 4, "%s: 4 corners on the weld outline (%d)" % (name, len(cs)))
    letters = "ABCD"
    for k in range(len(cs) if len(cs) == 4 else 0):
        a, b = cs[k], cs[(k + 1) % 4]
        arc = sum(math.dist(w[j % len(w)], w[(j + 1) % len(w)]) for j in range(a, b if b > a else b + len(w)))
        printed = number(labels, "edge %s-%s" % (letters[k], letters[(k + 1) % 4]))
        chk.check(abs(printed - arc) <= 0.051, "%s: edge %s-%s printed %.1f mm = its arc length %.4f mm"
                  % (name, letters[k], letters[(k + 1) % 4], printed, arc))
        near = [t for t in texts if t.dxf.text == letters[k]]
        chk.check(len(near) == 1 and min(range(4), key=lambda j: math.dist((near[0].dxf.insert[0], near[0].dxf.insert[1]), w[cs[j]])) == k,
                  "%s: the letter %s marks corner %s" % (name, letters[k], letters[k]))
    if len(cs) == 4:
        for a, b in ((0, 2), (1, 3)):
            d = math.dist(w[cs[a]], w[cs[b]])
            printed = number(labels, "diagonal %s-%s" % (letters[a], letters[b]))
            chk.check(abs(printed - d) <= 0.051, "%s: diagonal %s-%s printed %.1f mm = the corners' distance %.4f mm"
                      % (name, letters[a], letters[b], printed, d))
    outlines = cut + weld
    lo, hi = doc.header.get("$EXTMIN"), doc.header.get("$EXTMAX")
    bad, off = [], []
    for t in texts:
        box = text_box(t)
        for e in outlines:
            p = points(e)
            if any(seg_meets_box(a, b, box) for a, b in zip(p, p[1:] + p[:1])):
                bad.append(t.dxf.text)
                break
        if box[0] < lo[0] - 1e-6 or box[1] < lo[1] - 1e-6 or box[2] > hi[0] + 1e-6 or box[3] > hi[1] + 1e-6:
            off.append(t.dxf.text)
    chk.check(texts and not bad, "%s: none of %d text boxes crosses an outline %s" % (name, len(texts), bad))
    chk.check(texts and not off, "%s: every text box lies on the sheet ($EXTMIN/$EXTMAX) %s" % (name, off))
    svg = open(os.path.join(tmp, "strips_%s.svg" % name)).read()
    chk.check('<g id="scale"' in svg and all(('<g id="%s"' % g) in svg for g in ("outline", "weld", "md", "text"))
              and all(">%s</text>" % t in svg for t in labels if "&" not in t and "<" not in t),
              "%s: the SVG has the same groups and labels and a scale bar" % name)


with scratch_dir() as tmp:
    chk.check(ezdxf is not None, "ezdxf is installed (apt-get install python3-ezdxf; scripts/setup does)")
    cyl = pm.cylinder_strip()
    nodes, tris, groups = pm.combine([("cylinder", cyl, (0, 0, 0)),
                                      ("cone", pm.cone_strip(), (0, 0, 3000)),
                                      ("sphere", pm.sphere_strip(), (0, 0, 6000))])
    groups["weld_bottom"] = (1, cyl[2]["bottom"])  # a named line on the cylinder's edge, labelled
    msh = os.path.join(tmp, "strips.msh")
    pm.write_msh(msh, nodes, tris, groups)
    base = ["-analysis", "cutpattern", "-mesh_file", msh, "-output_file", os.path.join(tmp, "strips.h5")]
    out = run(etfe, base + ["-cutpattern_seam_allowance", ALLOW, "-cutpattern_roll_width", ROLL,
                            "-cutpattern_roll_gap", GAP])[1]
    print("\n".join(l for l in out.splitlines() if "edge" in l or "area" in l or "nesting" in l or "WARN" in l))
    if ezdxf is not None:
        for name in ("cylinder", "cone", "sphere"):
            check_strip(tmp, name)

    # --- the nesting
    m = re.search(r"roll length ([\d.]+) mm.*waste ([-\d.]+) %", out)
    chk.check(m is not None, "the roll length used and the waste are printed")
    nest = os.path.join(tmp, "strips_nesting.dxf")
    if ezdxf is not None and m and os.path.exists(nest):
        doc = ezdxf.readfile(nest)
        cut = [points(e) for e in polylines(doc, "OUTLINE")]
        chk.check(len(cut) == 3 and all(e.is_closed for e in polylines(doc, "OUTLINE")),
                  "nesting: the 3 strips' closed cut outlines (%d)" % len(cut))
        ys = [p[1] for c in cut for p in c]
        chk.check(min(ys) >= -1e-6 and max(ys) <= ROLL + 1e-6, "nesting: every strip within the roll's width: y in "
                  "[%.4f, %.4f] of [0, %g]" % (min(ys), max(ys), ROLL))
        boxes = [(min(p[0] for p in c), min(p[1] for p in c), max(p[0] for p in c), max(p[1] for p in c)) for c in cut]
        apart = all(a[2] + GAP - 1e-6 <= b[0] or b[2] + GAP - 1e-6 <= a[0] or a[3] + GAP - 1e-6 <= b[1] or
                    b[3] + GAP - 1e-6 <= a[1] for i, a in enumerate(boxes) for b in boxes[i + 1:])
        chk.check(apart, "nesting: no two strips overlap (their boxes %g mm apart)" % GAP)
        length = max(b[2] for b in boxes)
        waste = 100 * (1 - sum(abs(area(c)) for c in cut) / (ROLL * length))
        print("nesting: roll length %.1f mm printed, %.4f mm drawn; waste %.2f %% printed, %.4f %% from the outlines"
              % (float(m.group(1)), length, float(m.group(2)), waste))
        chk.check(abs(float(m.group(1)) - length) <= 0.051 and abs(float(m.group(2)) - waste) <= 0.0051,
                  "nesting: the printed roll length and waste agree with the drawn outlines")
        chk.check(os.path.exists(os.path.join(tmp, "strips_nesting.svg")), "nesting: the SVG is written")
    rc, narrow = run(etfe, base + ["-cutpattern_roll_width", 500], expect_fail=None)
    m = re.search(r"strip (\w+) is ([\d.]+) mm wide", narrow)
    chk.check(rc != 0 and m is not None and m.group(1) in ("cylinder", "cone", "sphere") and float(m.group(2)) > 500,
              "a roll narrower than a strip is refused naming the strip and its width: %s"
              % (m.group(0) if m else narrow.strip().splitlines()[-1:]))

    # --- the fabrication errors
    path = os.path.join(tmp, "strips_errors.csv")
    rows = list(csv.DictReader(open(path))) if os.path.exists(path) else []
    chk.check(len(rows) > 0, "the errors CSV is written (%d rows)" % len(rows))
    for name in ("cylinder", "cone"):
        r = [x for x in rows if x["strip"] == name]
        worst = max([abs(float(x["error"])) for x in r] + [float(x["max_link_error"]) for x in r], default=math.nan)
        chk.check(len([x for x in r if x["kind"] == "edge"]) == 4 and worst < 1e-6,
                  "%s (developable): every edge, area and link error below 1e-6 (largest %.2e)" % (name, worst))
    sph = {x["kind"] + ":" + x["name"]: x for x in rows if x["strip"] == "sphere"}
    inner = float(sph["interior:interior links"]["max_link_error"]) if "interior:interior links" in sph else 0
    astrain = float(sph["area:area"]["error"]) if "area:area" in sph else 0
    chk.check(inner > 1e-3 and abs(astrain) > 1e-3 and re.search(r"strip sphere area: .*area strain", out),
              "sphere (doubly curved): interior link error %.3e and area strain %.3e reported" % (inner, astrain))
    # Above the first-yield strain (S_y1 4 MPa / E 800 MPa = 0.5 %): a warning naming the strip.
    out = run(etfe, base + ["-cutpattern_strips", "sphere", "-material_yield", 4])[1]
    warn = [l for l in out.splitlines() if "WARNING" in l]
    chk.check(any("strip sphere interior" in l and "first-yield strain 0.500 %" in l for l in warn),
              "an error above the first-yield strain is warned about, naming the strip: %s" % warn[:1])
chk.finish()
