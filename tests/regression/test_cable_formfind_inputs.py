"""Form finding with a cable's force density or target sag (docs/cables.md "Form finding",
docs/theory.md §14), on the flat 2 m square film of stress n = 1 MPa x 0.25 mm held on its west
and east edges, the south and north edges cables (20 segments each):

* -cable_<g>_sag s: the force printed is n R with R = (c^2/4 + s^2) / (2 s) (chord c = 2000 mm),
  the cables carry it, and the found edges' midpoints sag by s (within the mesh error);
* -cable_<g>_force_density q: every found segment carries q times its length, the edge is the
  circle of that force (R = q l / n: the segments come out equally long), and the cut length
  printed is the sum of l_i / (1 + q l_i / EA);
* bad inputs refused by name.
"""
import math
import os
import re

import etfe_testlib as T
from etfe_testlib import run, scratch_dir
import cable_meshes

LINE = re.compile(r"formfind: cable (\w+) \((\d+) segments\): force min = (\S+) N, max = (\S+) N, "
                  r"length = (\S+) mm, cut_length = (\S+) mm")
SAG = re.compile(r"structure: cable (\w+): target sag (\S+) mm over the chord (\S+) mm: edge radius R = \(c\^2/4 \+ "
                 r"s\^2\) / \(2 s\) = (\S+) mm, film stress n = \S+ MPa x \S+ mm = (\S+) N/mm, cable force T = n R = (\S+) N")
EA, N_FILM = 1e5, 1.0 * 0.25


def test(etfe, chk):
    with scratch_dir("etfe-cable-ff") as tmp:
        sq, found = os.path.join(tmp, "square.msh"), os.path.join(tmp, "found.msh")
        cable_meshes.square(sq, 2000.0, 20)
        ff = ["-scene", "structure", "-analysis", "formfind", "-mesh_file", sq, "-membrane_thickness", 0.25,
              "-formfind_stress", 1, "-formfind_mesh_control", "false", "-formfind_tol", 1e-6, "-formfind_monitor", 0,
              "-bc_west_fix", "xyz", "-bc_east_fix", "xyz", "-cable_south_EA", EA, "-cable_north_EA", EA,
              "-formfind_mesh_out", found]

        # --- Target sag 150 mm: R = (1000^2 + 150^2) / 300 = 3408.33 mm, T = n R = 852.08 N.
        s = 150.0
        _, out = run(etfe, ff + ["-output", 0, "-cable_south_sag", s, "-cable_north_sag", s])
        R = (2000.0 ** 2 / 4 + s * s) / (2 * s)
        notes = {m.group(1): m for m in SAG.finditer(out)}
        cab = {m.group(1): m for m in LINE.finditer(out)}
        xyz = cable_meshes.read_nodes41(found)
        for name, mid, y_chord, inward in (("south", 10, 0.0, 1.0), ("north", 20 * 21 + 10, 2000.0, -1.0)):
            m = notes.get(name)
            chk.check(m is not None, "sag: the force of cable %s is printed before form finding" % name)
            if m is None:
                continue
            Tp = float(m.group(6))
            chk.less(abs(Tp / (N_FILM * R) - 1), 1e-9, "sag: cable %s's printed force %.9e N against n R = %.9e N, "
                                                       "relative difference" % (name, Tp, N_FILM * R))
            c = cab[name]
            chk.check(float(c.group(3)) == float(c.group(4)) and abs(float(c.group(4)) / Tp - 1) < 1e-6,
                      "sag: cable %s carries the printed force (min %s, max %s N)" % (name, c.group(3), c.group(4)))
            sag = inward * (xyz[mid + 1][1] - y_chord)
            chk.less(abs(sag - s), 0.1, "sag: found edge %s's midpoint sags %.4f mm against the target %g mm "
                                        "(20 segments), mm off" % (name, sag, s))
            L = float(c.group(5))
            chk.less(abs(float(c.group(6)) - L / (1 + Tp / EA)), 1e-5,
                     "sag: cable %s's cut length %s mm is l / (1 + T/EA)" % (name, c.group(6)))

        # --- Force density q = 5 N/mm (about 500 N on the 100 mm segments): each segment's force is q l.
        q, h5 = 5.0, os.path.join(tmp, "fd.h5")
        _, out = run(etfe, ff + ["-output", 1, "-output_file", h5, "-cable_south_force_density", q,
                                 "-cable_north_force_density", q])
        cab = {m.group(1): m for m in LINE.finditer(out)}
        data = T.read_steps(h5)[-1][2]
        force, length, which = data.get("cables/force"), data.get("cables/length"), data.get("cables/cable")
        chk.check(force is not None and len(force) == 40, "force density: 40 segment forces in the results file")
        if force is not None:
            worst = max(abs(f - q * l) / (q * l) for f, l in zip(force, length))
            chk.less(worst, 1e-14, "force density: segment forces against q l (%.3f-%.3f N), largest relative "
                                   "difference" % (min(force), max(force)))
            # The film's isotropic stress pulls each edge node across the edge only, so the segments come
            # out equally long and the edge is the circle of a constant force q l: R = q l / n.
            xyz = cable_meshes.read_nodes41(found)
            Rq = q * sum(length) / len(length) / N_FILM
            sag = xyz[11][1]
            circle = Rq - math.sqrt(Rq * Rq - 1000.0 ** 2)
            chk.less(abs(sag - circle), 0.2, "force density: found edge south's midpoint sags %.4f mm against %.4f mm of "
                                             "the circle R = q l / n = %.3f mm, mm off" % (sag, circle, Rq))
            for k, name in enumerate(("south", "north")):  # the scene's order: the options' order of the groups
                sel = [i for i in range(len(force)) if which[i] == k]
                cut = sum(length[i] / (1 + force[i] / EA) for i in sel)
                got = [v for v in cab.values() if abs(float(v.group(5)) - sum(length[i] for i in sel)) < 1e-5]
                chk.check(len(got) >= 1 and abs(float(got[0].group(6)) - cut) < 1e-5,
                          "force density: a cable's cut length is the sum of l_i / (1 + q l_i / EA) = %.6f mm" % cut)

        # --- Bad inputs, each refused by name before the run.
        bad = [(["-cable_south_sag", s, "-cable_south_prestress", 500, "-cable_north_prestress", 500],
                r"cable south: -cable_south_prestress and -cable_south_sag both set the cable's force"),
               (["-cable_south_force_density", q, "-cable_south_sag", s, "-cable_north_prestress", 500],
                r"cable south: -cable_south_force_density and -cable_south_sag both set"),
               (["-cable_south_sag", 0, "-cable_north_prestress", 500], r"-cable_south_sag 0: an edge cable's sag is positive"),
               (["-cable_south_sag", 1000, "-cable_north_prestress", 500],
                r"-cable_south_sag 1000: the sag of a circular edge is below half its chord \(2000\.000000 mm"),
               (["-cable_south_force_density", -1, "-cable_north_prestress", 500],
                r"-cable_south_force_density -1: a cable's force density is positive"),
               (["-cable_south_force_density", q, "-cable_south_sliding", "-cable_north_prestress", 500],
                r"cable south: -cable_south_sliding with -cable_south_force_density: a pocket carries one force"),
               (["-cable_south_sag", s, "-cable_south_length", 2000, "-cable_north_prestress", 500],
                r"cable south: -cable_south_sag sets the cable's force and its cut length follows; drop -cable_south_length"),
               (["-cable_south_sag", s, "-cable_north_prestress", 500, "-film_film_stress_ratio", 2],
                r"-cable_south_sag: the film beside cable south has the stress ratio MD:TD = 2"),
               (["-cable_south_sag", s, "-cable_north_prestress", 500, "east free"],
                r"-cable_south_sag: cable south's end node 20 .* is not held in x, y and z")]
        k = ff.index("-bc_east_fix")
        east_free = ff[:k] + ff[k + 2:]  # the south cable's east end not held
        for args, pattern in bad:
            base = east_free if "east free" in args else ff
            _, out = run(etfe, base + ["-output", 0] + [a for a in args if a != "east free"], expect_fail=True)
            chk.check(re.search(pattern, out), "refused: %s (%s)" % (" ".join(map(str, args)), pattern))
        static = ["-scene", "structure", "-mesh_file", sq, "-membrane_thickness", 0.25, "-output", 0,
                  "-bc_west_fix", "xyz", "-bc_east_fix", "xyz", "-cable_south_EA", EA]
        for opt, v in (("sag", s), ("force_density", q)):
            _, out = run(etfe, static + ["-cable_south_" + opt, v], expect_fail=True)
            chk.check(re.search(r"-cable_south_%s: a form-finding input \(-analysis formfind\)" % opt, out),
                      "refused: -cable_south_%s in a static run" % opt)


T.main(test)
