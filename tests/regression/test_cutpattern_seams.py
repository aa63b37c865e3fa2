"""Seams as conforming lines and strips that fit the roll (-analysis cutpattern):
  * a developable cone cut by geodesic and by planar seams (-cutpattern_strip_layout geodesic,
    parallel): every strip flattens exactly, every link and every seam keeps its 3D length
    (1e-9): near a developable bend no node is moved;
  * a hypar cut by planes (-cutpattern_strip_layout parallel, W 205 mm so the planes pass near
    nodes): the seam is the plane section itself, every seam node on its plane (1e-9 mm: nodes
    near it are moved onto it, none is taken off it), the largest turn between consecutive seam
    segments below 3 deg, the smallest triangle quality at least the relocation fraction 0.2 times
    the mesh's; the same for the hypar turned by 45 deg (a saddle), whose plane sections are
    parabolas;
  * a 3 m x 8 m cushion (two foils, scripts/cushion-mesh, lens 300 mm) on a 1.5 m roll with a
    15 mm seam allowance (-cutpattern_strip_fit_roll): both physical surfaces are cut, every
    flattened strip with the allowance on both sides fits the roll (measured from the pattern
    meshes), and the nesting places them all; the uncut foil's largest link error is printed
    beside the strips';
  * a round cushion cut in radial gores (-cutpattern_strip_layout radial): 10 per foil;
  * the PDF sheets of a strip and of the nesting: valid cross-reference table, the page the SVG's
    size at 1:1;
  * the form-found DD1511 saddle (corner and middle surfaces) cut directly on a 600 mm roll: every
    strip fits; the patterns are the fit's last flattenings (no second pass), equal to the cut
    surface's strips flattened anew.
"""
import math
import os
import re
import subprocess
import sys

import pattern_meshes as pm
from etfe_testlib import Checker, REPO, etfe_path, form_found_saddle, scratch_dir

etfe = etfe_path()
chk = Checker("cutpattern_seams")
NUM = pm.NUM


def line_lengths(out):
    return [(float(a), float(b)) for a, b in re.findall(
        r"cutpattern: strip \S+ line cut_\S+: 3D %s mm, 2D %s mm" % (NUM, NUM), out)]


SEAMS = re.compile(r"smallest triangle quality %s \(input %s\); seams: (\d+) mesh nodes moved onto them \(%s mm at "
                   r"most\), (\d+) crossings taken to a node that could not move, seams within %s mm of the traced "
                   r"lines, largest turn between seam segments %s deg" % (NUM, NUM, NUM, NUM, NUM))


def parallel_cut(tmp, name, mesh):
    """Cuts mesh (nodes, triangles, ...) into strips by planes y = const 205 mm apart: the match of
    its seams line (SEAMS, None if missing), how far its seam nodes lie off their planes (largest
    y range of a cut_* group, mm) and its link errors per strip."""
    path = os.path.join(tmp, name + ".msh")
    pm.write_msh(path, mesh[0], mesh[1], {})
    out = pm.cutpattern(etfe, tmp, name, path, ["-cutpattern_strip_width", 205, "-cutpattern_strip_direction", "x",
                                                "-cutpattern_strip_layout", "parallel"])
    groups = pm.msh41_point_groups(os.path.join(tmp, name + "_cut.msh"))
    off_plane = max(max(p[1] for p in v) - min(p[1] for p in v) for k, v in groups.items() if k.startswith("cut_"))
    return SEAMS.search(out), off_plane, pm.link_errors(out)


def least_width(pts):
    """The least width of plane points: across the narrowest caliper of their convex hull."""
    p = sorted(set(pts))
    cross = lambda o, a, b: (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lower, upper = [], []
    for q in p:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], q) <= 0:
            lower.pop()
        lower.append(q)
    for q in reversed(p):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], q) <= 0:
            upper.pop()
        upper.append(q)
    h = lower[:-1] + upper[:-1]
    best = float("inf")
    for i in range(len(h)):
        a, b = h[i], h[(i + 1) % len(h)]
        L = math.hypot(b[0] - a[0], b[1] - a[1])
        if L > 0:
            best = min(best, max(abs(cross(a, b, q)) / L for q in h))
    return best


def strip_widths(tmp, name, strips):
    return {s: least_width([(x, y) for x, y, _ in pm.read_msh41_nodes(
        os.path.join(tmp, "%s_%s.msh" % (name, s))).values()]) for s in strips}


with scratch_dir() as tmp:
    # 1. A cone (developable), 24 x 16 cells, seams along its slant 90 mm apart.
    cone = pm.cone_strip(nx=24, ny=16)
    path = os.path.join(tmp, "cone.msh")
    pm.write_msh(path, cone[0], cone[1], {})
    for layout in ("geodesic", "parallel"):
        out = pm.cutpattern(etfe, tmp, "cone_" + layout, path, ["-cutpattern_strip_width", 90,
                                                                "-cutpattern_strip_direction", "z",
                                                                "-cutpattern_strip_layout", layout])
        errs, lines = pm.link_errors(out), line_lengths(out)
        worst_line = max(abs(l2 - l3) / l3 for l3, l2 in lines) if lines else float("nan")
        print("cone, %s seams: strips %s, largest link error %.2e, largest seam length error %.2e" % (
            layout, sorted(errs), max(errs.values()) if errs else float("nan"), worst_line))
        chk.check(len(errs) == 4 and max(errs.values()) < 1e-9,
                  "cone, %s seams: 4 strips, each flattens exactly (every link to 1e-9)" % layout)
        chk.check(len(lines) == 6 and worst_line < 1e-9, "cone, %s seams: every seam keeps its length (1e-9)" % layout)

    # 2. A hypar 1000 x 1000 mm, rise 200 mm, 24 x 24 cells, cut by planes y = const 205 mm
    # apart along the surface (the grid's lines are 41.7 mm apart: the planes pass 3 mm from nodes).
    hyp = pm.hypar(n=24)
    m, off_plane, errs = parallel_cut(tmp, "hyp", hyp)
    print("hypar, planar seams 205 mm apart: %d strips, quality %s (input %s), %s nodes moved onto the seams (up "
          "to %s mm), %s crossings taken to a fixed node, largest turn %s deg, seam nodes off their plane by %.2e mm"
          % ((len(errs),) + (m.groups() if m else ("?",) * 7)[:2] + (m.groups() if m else ("?",) * 7)[2:4] +
             ((m.group(5), m.group(7)) if m else ("?", "?")) + (off_plane,)))
    chk.check(m is not None and int(m.group(3)) > 0, "hypar: mesh nodes near the planes are moved onto them")
    chk.check(off_plane < 1e-9, "hypar: every seam node lies on its plane (1e-9 mm): the seam is the section")
    chk.check(m is not None and float(m.group(7)) < 3.0, "hypar: largest turn between seam segments below 3 deg")
    chk.check(m is not None and float(m.group(1)) >= 0.2 * float(m.group(2)),
              "hypar: smallest triangle quality at least 0.2 x the mesh's")
    chk.check(len(errs) == 6 and max(errs.values()) < 0.05, "hypar: 6 strips, flattened")

    # 2b. The same hypar turned by 45 deg (the saddle z = 0.4 (x^2 - y^2) / 1000 mm over 1000 x 1000 mm,
    # 24 x 24 cells): the planes y = const cut it in parabolas, curved seams.
    sad = pm.grid(24, 24, lambda u, v: ((u - 0.5) * 1000, (v - 0.5) * 1000, 400 * ((u - 0.5) ** 2 - (v - 0.5) ** 2)))
    m, off_plane, errs = parallel_cut(tmp, "sad", sad)
    print("saddle (hypar at 45 deg), planar seams 205 mm apart: %s" % (m.group(0) if m else "?"))
    print("  seam nodes off their plane by %.2e mm" % off_plane)
    chk.check(off_plane < 1e-9, "saddle: every seam node lies on its plane (1e-9 mm)")
    chk.check(m is not None and float(m.group(7)) < 3.0,
              "saddle: the curved seams turn by less than 3 deg between consecutive segments")
    chk.check(m is not None and int(m.group(5)) == 0, "saddle: no crossing taken to a node (no step in a seam)")
    chk.check(m is not None and float(m.group(1)) >= 0.2 * float(m.group(2)),
              "saddle: smallest triangle quality at least 0.2 x the mesh's")
    chk.check(len(errs) == 6 and max(errs.values()) < 0.05, "saddle: 6 strips, flattened")

    # 3. A 3 m x 8 m cushion, two foils (physical surfaces top, bottom), on a 1.5 m roll.
    path = os.path.join(tmp, "cushion.msh")
    subprocess.run([sys.executable, os.path.join(REPO, "scripts", "cushion-mesh"), path, "--rectangle", "3000,8000",
                    "--lens", "300mm", "--size", "150"], check=True, capture_output=True)
    whole = pm.link_errors(pm.cutpattern(etfe, tmp, "whole", path, []))
    out = pm.cutpattern(etfe, tmp, "cush", path, ["-cutpattern_roll_width", 1500, "-cutpattern_seam_allowance", 15,
                                                  "-cutpattern_strip_fit_roll", "-cutpattern_strip_direction", "y"])
    errs = pm.link_errors(out)
    widths = strip_widths(tmp, "cush", errs)
    nest = re.search(r"nesting on a roll 1500.0 mm wide: roll length %s mm" % NUM, out)
    print("cushion 3 m x 8 m: uncut foils %s; strips on a 1.5 m roll: %s" % (
        ", ".join("%s link error max %.2e" % kv for kv in sorted(whole.items())),
        ", ".join("%s %.1f mm wide, link error max %.2e" % (s, widths[s], errs[s]) for s in sorted(errs))))
    chk.check(sorted(errs) == ["bottom_01", "bottom_02", "bottom_03", "top_01", "top_02", "top_03"],
              "cushion: both foils cut, 3 strips each")
    chk.check(widths and max(widths.values()) + 2 * 15 <= 1500, "cushion: every strip with its allowance fits 1500 mm")
    chk.check(nest is not None, "cushion: the nesting places every strip on the roll")
    chk.check(whole and errs and max(errs.values()) < max(whole.values()),
              "cushion: the strips' largest link error is below the uncut foil's")

    # The PDF sheets: one per strip and the nesting; the page is the SVG's size at 1:1 (an 8 m strip
    # is longer than PDF's 5.08 m page limit: /UserUnit 2), the cross-reference table points at
    # every object.
    for base in ("cush_top_01", "cush_nesting"):
        pdf = open(os.path.join(tmp, base + ".pdf"), "rb").read().decode("latin-1")
        svg = open(os.path.join(tmp, base + ".svg")).read()
        sw, sh = (float(x) for x in re.search(r'width="%smm" height="%smm"' % (NUM, NUM), svg).groups())
        box = [float(x) for x in re.search(r"/MediaBox \[0 0 %s %s\]" % (NUM, NUM), pdf).groups()]
        unit = float(re.search(r"/UserUnit (\d+)", pdf).group(1)) if "/UserUnit" in pdf else 1.0
        xref = int(re.search(r"startxref\n(\d+)", pdf).group(1))
        offsets = [int(l[:10]) for l in pdf[xref:].split("\n")[3:] if re.match(r"\d{10} 00000 n", l)]
        objs_ok = all(re.match(r"%d 0 obj" % (k + 1), pdf[o:]) for k, o in enumerate(offsets))
        size_ok = abs(box[0] * unit * 25.4 / 72 - sw) < 1e-2 and abs(box[1] * unit * 25.4 / 72 - sh) < 1e-2
        print("%s.pdf: %d objects, page %.1f x %.1f mm (UserUnit %g), SVG %.1f x %.1f mm" % (
            base, len(offsets), box[0] * unit * 25.4 / 72, box[1] * unit * 25.4 / 72, unit, sw, sh))
        chk.check(pdf.startswith("%PDF-1.6") and pdf.rstrip().endswith("%%EOF") and objs_ok and len(offsets) == 6,
                  "%s.pdf: a PDF whose cross-reference table points at its 6 objects" % base)
        chk.check(size_ok, "%s.pdf: the page is the drawing at 1:1 (the SVG's size, 0.01 mm)" % base)

    # 3b. A round cushion (R 1500 mm, lens 200 mm, 48 sectors) cut in radial gores, W 950 mm: the
    # rim 9425 mm long gives 10 gores per foil (36 deg: across the mesh's 7.5 deg sectors).
    path = os.path.join(tmp, "round.msh")
    subprocess.run([sys.executable, os.path.join(REPO, "scripts", "cushion-mesh"), path, "--circle", "1500",
                    "--lens", "200mm", "--size", "100"], check=True, capture_output=True)
    out = pm.cutpattern(etfe, tmp, "round", path, ["-cutpattern_strip_width", 950,
                                                   "-cutpattern_strip_layout", "radial"])
    errs = pm.link_errors(out)
    m = re.search(r"radial strips of top: .*", out)
    print("round cushion, radial gores: %s; link error max %.2e" % (m.group(0) if m else "?",
                                                                   max(errs.values()) if errs else float("nan")))
    chk.check(sorted(errs) == sorted(["%s_%02d" % (f, k) for f in ("bottom", "top") for k in range(1, 11)]),
              "round cushion: radial seams cut each foil into 10 gores")
    chk.check(errs and max(errs.values()) < 0.01, "round cushion: every gore flattens (link error below 1 %)")

    # 4. The form-found DD1511 saddle (physical surfaces corner and middle) cut on a 600 mm roll.
    msh = form_found_saddle(etfe, tmp)
    out = pm.cutpattern(etfe, tmp, "dd", msh, ["-cutpattern_roll_width", 600, "-cutpattern_seam_allowance", 15,
                                               "-cutpattern_strip_fit_roll"])
    errs = pm.link_errors(out)
    widths = strip_widths(tmp, "dd", errs)
    print("DD1511 saddle on a 600 mm roll: %s" % ", ".join("%s %.1f mm" % kv for kv in sorted(widths.items())))
    chk.check(any(s.startswith("corner_") for s in errs) and any(s.startswith("middle_") for s in errs) and
              len(errs) >= 4, "DD1511: both surfaces cut into strips")
    chk.check(widths and max(widths.values()) + 30 <= 600, "DD1511: every strip with its allowance fits 600 mm")
    chk.check(re.search(r"nesting on a roll 600.0 mm wide", out) is not None, "DD1511: nested on the roll")
    # The patterns are the fit's own flattenings (no second pass over the strips), and they are what
    # flattening the cut surface's strips (dd_cut.msh) anew gives: the same S and cut line lengths.
    again = pm.cutpattern(etfe, tmp, "again", os.path.join(tmp, "dd_cut.msh"), [])
    strip_s = r"cutpattern: strip (\S+): \d+ nodes, \d+ links, \d+ iterations .*? S = (\S+) mm\^2"
    fit_s, new_s = re.findall(strip_s, out), re.findall(strip_s, again)
    reused = re.search(r"the patterns are the roll fit's flattenings of its last try \((\d+) strips, not flattened "
                       r"again\)", out)
    print("DD1511: %s; flattened again from dd_cut.msh: %d strips, the same S and line lengths: %s" % (
        reused.group(0) if reused else "the patterns were flattened again", len(new_s),
        sorted(fit_s) == sorted(new_s) and sorted(line_lengths(out)) == sorted(line_lengths(again))))
    chk.check(reused is not None and int(reused.group(1)) == len(errs),
              "DD1511: the patterns are the roll fit's last flattenings, not flattened a second time")
    chk.check(len(fit_s) == len(errs) and sorted(fit_s) == sorted(new_s) and
              sorted(line_lengths(out)) == sorted(line_lengths(again)),
              "DD1511: the fit's patterns equal the cut strips flattened anew (S and every cut line's lengths)")

    # A fit without a roll is refused naming the options.
    out = pm.cutpattern(etfe, tmp, "noroll", path, ["-cutpattern_strip_fit_roll"], expect_fail=True)
    chk.check("-cutpattern_strip_fit_roll needs the roll" in out, "a fit without -cutpattern_roll_width is refused")
chk.finish()
