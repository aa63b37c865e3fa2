"""Geodesic seams started from a user's line (-cutpattern_strip_start <1-D group>):
  * a hypar z = 0.8 x y / 1000 mm over 1000 x 1000 mm (24 x 24 cells) with a 1-D group along the
    ruling x = -125 mm (y from -417 to +333 mm; a straight line on the surface, so a geodesic):
    the first seam, started at the group's middle node along it, passes through every node of the
    group (within 1e-6 of the surface's size, 1000 mm); without the option the seams pass through
    the middle (x = 0) and x = +-205 mm, +-410 mm, not through the group; the strips are flattened;
  * refused by name: a group that does not exist, a 2-D group, a line with a node on no triangle.
"""
import math
import os

import pattern_meshes as pm
from etfe_testlib import Checker, etfe_path, scratch_dir
import re

etfe = etfe_path()
chk = Checker("cutpattern_start_line")
N = 24


with scratch_dir() as tmp:
    nodes, tris, _ = pm.hypar(n=N)
    idx = lambda i, j: j * (N + 1) + i
    line = [(idx(9, j), idx(9, j + 1)) for j in range(2, 20)]  # x = -125 mm, y = -417 .. +417 mm
    groups = {"start": (1, line), "film": (2, list(range(len(tris))))}
    path = os.path.join(tmp, "hyp.msh")
    pm.write_msh(path, nodes, tris, groups)
    pts = [nodes[a] for a, _ in line] + [nodes[line[-1][1]]]

    def seam_distance(name):
        cut = pm.msh41_point_groups(os.path.join(tmp, name + "_cut.msh"))
        seam = [p for k, v in cut.items() if k.startswith("cut_") for p in v]
        return max(min(math.dist(p, q) for q in seam) for p in pts) if seam else float("inf")

    args = ["-cutpattern_strip_width", 205, "-cutpattern_strip_direction", "y"]
    out = pm.cutpattern(etfe, tmp, "old", path, args)
    d_old = seam_distance("old")
    print("without -cutpattern_strip_start: the group's nodes lie up to %.3f mm from the seams" % d_old)
    chk.check(d_old > 10, "without the option the seams do not pass through the group (the test can fail)")

    out = pm.cutpattern(etfe, tmp, "hyp", path, args + ["-cutpattern_strip_start", "start"])
    d = seam_distance("hyp")
    errs = pm.link_errors(out)
    m = re.search(r"geodesic strips of film: .*", out)
    print(m.group(0) if m else "?")
    print("with -cutpattern_strip_start start: the group's %d nodes lie at most %.3e mm from the seams; %d strips, "
          "largest link error %s" % (len(pts), d, len(errs), max(errs.values()) if errs else "?"))
    chk.check(d < 1e-6 * 1000, "the first seam passes through every node of the start line (1e-6 of 1000 mm)")
    chk.check(m is not None and "lines along the start line start" in m.group(0), "the note names the start line")
    chk.check(len(errs) >= 4 and max(errs.values()) < 0.05, "at least 4 strips, all flattened")

    # Refusals, by name.
    out = pm.cutpattern(etfe, tmp, "none", path, args + ["-cutpattern_strip_start", "nosuch"], expect_fail=True)
    chk.check("-cutpattern_strip_start nosuch" in out and "no physical group of that name" in out,
              "a group that does not exist is refused by name")
    out = pm.cutpattern(etfe, tmp, "twod", path, args + ["-cutpattern_strip_start", "film"], expect_fail=True)
    chk.check("-cutpattern_strip_start film" in out and "not 1-D" in out, "a 2-D group is refused by name")
    off = os.path.join(tmp, "off.msh")
    pm.write_msh(off, nodes + [(0.0, 0.0, 500.0)], tris,
                 {"start": (1, line + [(line[-1][1], len(nodes))]), "film": (2, list(range(len(tris))))})
    out = pm.cutpattern(etfe, tmp, "off", off, args + ["-cutpattern_strip_start", "start"], expect_fail=True)
    chk.check("-cutpattern_strip_start start" in out and "does not lie on the surface" in out,
              "a line with a node off the surface is refused by name")
chk.finish()
