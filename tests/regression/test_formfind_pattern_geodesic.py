"""Strips of a given width cut by geodesic lines: -analysis cutpattern -mesh_file
surface.msh -cutpattern_strip_width W. Meshes are made here (pattern_meshes.py).
  * a cylinder (developable) cut along its generators at W: every inner strip's flattened pattern
    is a rectangle (1e-9 mm), W wide to the snap distance (a crossing within 0.1 of an edge's
    length of a node is moved to it: here the lines lie on the mesh's generators, 0.016 mm off),
    and keeps every link length (1e-10);
  * a hypar (K < 0: geodesics part) cut at W: on the transverse geodesic each inner strip is W
    wide; in the flattened pattern its width stays within one element size h of W (the measured
    range is printed); the outline and every cutting line keep their 3D length, and both strips
    of a cutting line measure it alike, as for strips named by physical groups;
  * the cut surface <stem>_cut.msh reads back as physical-group strips with the same lines;
  * a mesh of two physical surfaces: each is cut into strips of its own;
  * bad input: W <= 0, W wider than the surface, W below the element size, a tube (the transverse line never ends), a sphere band whose lines meet:
    refused naming the option."""
import math
import os
import re
import time

import pattern_meshes as pm
from etfe_testlib import Checker, cutpattern_report, etfe_path, run, scratch_dir

etfe = etfe_path()
chk = Checker("formfind_pattern_geodesic")
NUM = r"([-+]?\d+\.?\d*(?:e[-+]?\d+)?)"


def cut(tmp, name, mesh, groups, width, direction, expect_fail=False):
    nodes, tris, _ = mesh
    path = os.path.join(tmp, name + ".msh")
    pm.write_msh(path, nodes, tris, groups)
    t0 = time.time()
    out = run(etfe, ["-analysis", "cutpattern", "-mesh_file", path, "-output_file", os.path.join(tmp, name + ".h5"),
                     "-cutpattern_strip_width", width, "-cutpattern_strip_direction", direction],
              expect_fail=expect_fail)[1]
    return out, time.time() - t0


def seg_dist(p, a, b):
    ab = (b[0] - a[0], b[1] - a[1])
    L2 = ab[0] ** 2 + ab[1] ** 2
    t = 0.0 if L2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / L2))
    return math.hypot(p[0] - a[0] - t * ab[0], p[1] - a[1] - t * ab[1])


def widths(tmp, name):
    """{strip: (min, max) distance in its flattened pattern from the nodes of one cutting line to
    the other} for the strips between two cutting lines (the pattern's long axis is x)."""
    out = {}
    for f in sorted(os.listdir(tmp)):
        m = re.match(r"%s_(\w+)\.msh$" % name, f)
        if not m or m.group(1) == "cut":  # <stem>_cut.msh is the cut 3D surface
            continue
        groups = pm.msh41_point_groups(os.path.join(tmp, f))
        cuts = sorted(g for g in groups if g.startswith("cut_"))
        if len(cuts) != 2:
            continue
        a, b = groups[cuts[0]], sorted(groups[cuts[1]])
        d = [min(seg_dist(p, b[i], b[i + 1]) for i in range(len(b) - 1)) for p in a]
        out[m.group(1)] = (min(d), max(d))
    return out


def report(out):
    rep = cutpattern_report(out)
    errs = {k: r["link_max"] for k, r in rep.items() if "link_max" in r}
    lines = [(k, name, l3, l2) for k, r in rep.items() for name, (l3, l2, _) in r["lines"].items()
             if name.startswith("cut_")]
    outline = {k: r["outline"][2] for k, r in rep.items() if "outline" in r}
    on_transverse = {m.group(1): float(m.group(2)) for m in re.finditer(
        r"geodesic strip (\w+): \d+ triangles, width on the transverse geodesic %s mm" % NUM, out)}
    return errs, lines, outline, on_transverse


with scratch_dir() as tmp:
    # Cylinder R 500 mm, 600 mm around (1.2 rad), 1000 mm along z, 24 x 20 cells: lines along z.
    W = 150.0
    cyl = pm.cylinder_strip(nx=24, ny=20)
    out, secs = cut(tmp, "cyl", cyl, {"cyl": (2, list(range(len(cyl[1]))))}, W, "z")
    errs, lines, outline, on_tr = report(out)
    wd = widths(tmp, "cyl")
    print("cylinder, W %g mm (%.2f s): strips %s" % (W, secs, sorted(errs)))
    for s in sorted(wd):
        print("  %s: width in the pattern %.9f .. %.9f mm, link error max %.2e" % (s, wd[s][0], wd[s][1], errs[s]))
    chk.check(len(errs) == 4 and len(wd) == 2, "cylinder: 3 lines at 0, +-%g mm give 4 strips, 2 of them inner" % W)
    chord = 2 * 500.0 * math.sin(0.6 / 24)  # the mesh's edges around the cylinder
    chk.check(all(hi - lo < 1e-9 for lo, hi in wd.values()),
              "cylinder: each inner pattern is a rectangle (its cutting lines parallel to 1e-9 mm)")
    chk.check(all(abs(lo - W) <= 0.1 * chord for lo, hi in wd.values()),
              "cylinder: each inner pattern is W = %g mm wide to the snap distance (0.1 x %.2f mm edge)" % (W, chord))
    chk.check(errs and max(errs.values()) < 1e-10, "cylinder: developable, every link keeps its length (1e-10)")
    chk.check(all(abs(l3 - 1000.0) < 1e-9 for _, _, l3, _ in lines),
              "cylinder: every cutting line is a generator, 1000 mm long")
    # The cut surface written beside the patterns reads back as physical-group strips, same lines.
    again = run(etfe, ["-analysis", "cutpattern", "-mesh_file", os.path.join(tmp, "cyl_cut.msh"),
                       "-output_file", os.path.join(tmp, "again.h5")])[1]
    chk.check(sorted(report(again)[1]) == sorted(lines),
              "cylinder: cyl_cut.msh (strips as physical surfaces) flattens to the same cutting lines")

    # Hypar 1000 x 1000 mm, rise 200 mm, 24 x 24 cells (h ~ 42..59 mm): lines along x (its
    # straight rulings y = const, which are geodesics; W chosen so no crossing is near a node).
    W = 220.0
    hyp = pm.hypar(n=24)
    h = 1000.0 / 24 * (1 + math.sqrt(2) + 1) / 3  # mean edge of the grid's cells (sides and diagonal)
    out, secs = cut(tmp, "hyp", hyp, {}, W, "x")
    errs, lines, outline, on_tr = report(out)
    wd = widths(tmp, "hyp")
    print("hypar, W %g mm, mean edge %.1f mm (%.2f s):" % (W, h, secs))
    for s in sorted(errs):
        w = wd.get(s)
        print("  %s: width on the transverse geodesic %.3f mm, in the pattern %s, link error max %.3e, "
              "outline expansion %.1e %%" % (s, on_tr.get(s, float("nan")),
                                             "%.3f .. %.3f mm" % w if w else "(edge strip)", errs[s], outline[s]))
    chk.check(len(errs) == 6 and len(wd) == 4, "hypar: lines at 0, +-220, +-440 mm give 6 strips, 4 inner")
    inner = [on_tr[s] for s in wd]
    chk.check(all(abs(w - W) < 1e-9 for w in inner), "hypar: inner strips W wide on the transverse geodesic")
    chk.check(all(W - h <= lo and hi <= W + h for lo, hi in wd.values()),
              "hypar: every inner pattern W +- one element size wide (%s)" % wd)
    chk.check(all(abs(e) < 1e-6 for e in outline.values()), "hypar: each outline keeps its 3D length (1e-6 %)")
    chk.check(all(abs(l2 - l3) < 1e-6 * l3 for _, _, l3, l2 in lines), "hypar: each cutting line keeps its length")
    by_line = {}
    for s, name, l3, l2 in lines:
        by_line.setdefault(name, []).append(l2)
    chk.check(len(by_line) == 5 and all(len(v) == 2 and abs(v[0] - v[1]) < 1e-6 for v in by_line.values()),
              "hypar: each of the 5 cutting lines measured alike in both its strips")
    chk.check(all(0 < e < 0.05 for e in errs.values()), "hypar: doubly curved strips flatten with small link errors")

    # A saddle z = 0.4 (x^2 - y^2) / 1000 mm (K < 0, the lines along x are no rulings: they bend
    # and the insertion snaps crossings near nodes), 24 x 24 cells, W 150 mm.
    W = 150.0
    sad = pm.grid(24, 24, lambda u, v: ((u - 0.5) * 1000, (v - 0.5) * 1000, 400 * ((u - 0.5) ** 2 - (v - 0.5) ** 2)))
    out, secs = cut(tmp, "sad", sad, {"saddle": (2, list(range(len(sad[1]))))}, W, "x")
    errs, lines, outline, on_tr = report(out)
    wd = widths(tmp, "sad")
    m = re.search(r"smallest triangle quality %s \(input %s\)" % (NUM, NUM), out)
    moved = max(float(x) for x in re.findall(r"inserted within %s mm of the traced geodesic" % NUM, out))
    print("saddle, W %g mm (%.2f s): smallest triangle quality %s (input %s), lines inserted within %.3f mm of "
          "the traced geodesics" % (W, secs, m.group(1) if m else "?", m.group(2) if m else "?", moved))
    for s in sorted(errs):
        w = wd.get(s)
        print("  %s: width on the transverse geodesic %.3f mm, in the pattern %s, link error max %.3e" % (
            s, on_tr.get(s, float("nan")), "%.3f .. %.3f mm" % w if w else "(edge strip)", errs[s]))
    chk.check(len(errs) == 8 and len(wd) == 6, "saddle: 7 lines, 8 strips (6 inner), all flattened")
    chk.check(all(W - h <= lo and hi <= W + h for lo, hi in wd.values()),
              "saddle: every inner pattern W +- one element size wide")
    chk.check(moved <= 0.2 * 60.0, "saddle: the lines within the snap distance (0.2 x the longest edge)")
    chk.check(m is not None and float(m.group(1)) >= 0.1, "saddle: no triangle of quality below 0.1 after insertion")
    chk.check(all(abs(e) < 1e-6 for e in outline.values()) and all(abs(l2 - l3) < 1e-6 * l3 for _, _, l3, l2 in lines),
              "saddle: outlines and cutting lines keep their 3D lengths")

    # Two physical surfaces (the cylinder's lower and upper halves) are each cut into strips of
    # their own (before, such a mesh was refused): a_01..a_04 and b_01..b_04, still developable.
    half = len(cyl[1]) // 2
    out, _ = cut(tmp, "two", cyl, {"a": (2, list(range(half))), "b": (2, list(range(half, len(cyl[1]))))}, W, "z")
    errs2 = report(out)[0]
    print("two physical surfaces: strips %s" % sorted(errs2))
    chk.check(sorted(errs2) == ["a_%02d" % k for k in range(1, 5)] + ["b_%02d" % k for k in range(1, 5)],
              "two physical surfaces: each cut into its own 4 strips")
    chk.check(errs2 and max(errs2.values()) < 1e-10, "two physical surfaces: every link keeps its length (1e-10)")

    # Bad input.
    for name, mesh, groups, width, direction, want in (
            ("zero", hyp, {}, -5, "x", "a strip width must be a positive length"),
            ("wide", hyp, {}, 5000, "x", "is wider than the surface"),
            ("thin", hyp, {}, 10, "x", "is narrower than the elements"),
            ("tube", pm.tube(n=24, ny=6), {}, 300, "z", "does not reach the boundary"),
            # A sphere band 3400 mm long (R 1000 mm): the lines along it, great circles, meet 1571 mm out.
            ("band", pm.sphere_strip(length=3400.0, width=1000.0, nx=34, ny=10), {}, 250, "y",
             "meets another cutting line")):
        out, _ = cut(tmp, name, mesh, groups, width, direction, expect_fail=True)
        chk.check(want in out and "-cutpattern_strip_width" in out, "%s: refused with \"%s\"" % (name, want))
    # A direction without a width would cut nothing: refused instead of silently ignored.
    path = os.path.join(tmp, "nowidth.msh")
    pm.write_msh(path, hyp[0], hyp[1], {})
    out = run(etfe, ["-analysis", "cutpattern", "-mesh_file", path, "-output_file", os.path.join(tmp, "nw.h5"),
                     "-cutpattern_strip_direction", "y"], expect_fail=True)[1]
    chk.check("-cutpattern_strip_direction only shapes geodesic strips" in out,
              "a direction without -cutpattern_strip_width is refused naming it")
chk.finish()
