"""Cables in the general scene (-cable_<group>_*, docs/cables.md; docs/theory.md §14).

* a straight cable pulled by a force: its force and length against EA E l / L0 (Green-Lagrange),
  the same numbers on 2 ranks;
* tension only: a cable whose end is pushed in goes slack and carries nothing;
* Irvine's elastic catenary (a cable under its weight between two supports at one level): the
  horizontal force and the midspan sag against the closed form;
* a sliding cable over a pulled-down node: one force along it (both end pulls equal), the loads
  balanced, the same on 2 ranks; the same cable fixed carries two different forces;
* form finding: a flat film of stress n with edge cables of force T: the edges are circles of
  radius T/n, the cut length l / (1 + T / EA); the four-point sail's edges curve by n/T, and its
  found mesh keeps the edge groups for the loaded run;
* cable forces, lengths and slack flags in the results file and the history CSV;
* a restart mid-load gives the uninterrupted run's results bit for bit;
* bad inputs refused by name.
The film under the cable in the static checks is nearly without stiffness (E = 0.001 MPa), so the
cable carries the load alone.
"""
import math
import os
import re

import etfe_testlib as T
from etfe_testlib import run, scratch_dir
import cable_meshes

FILM = ["-scene", "structure", "-material_type", "elastic", "-material_young", 1e-3, "-material_poisson", 0.3,
        "-membrane_thickness", 0.2, "-output", 0]
LINE = re.compile(r"(\w+): cable (\w+) \((\d+) segments(, sliding)?\): force min = (\S+) N, max = (\S+) N, "
                  r"length = (\S+) mm, cut_length = (\S+) mm, slack = (\d+) segments")
PULL = re.compile(r"(\w+): cable (\w+) end (\d) \(node \d+\): pull = \((\S+), (\S+), (\S+)\) N")


def cables(out):
    """{name: dict(min, max, length, cut, slack, sliding, pull=[(x, y, z), (x, y, z)])}"""
    res = {}
    for m in LINE.finditer(out):
        res[m.group(2)] = dict(min=float(m.group(5)), max=float(m.group(6)), length=float(m.group(7)),
                               cut=float(m.group(8)), slack=int(m.group(9)), sliding=bool(m.group(4)), pull=[None, None])
    for m in PULL.finditer(out):
        res[m.group(2)]["pull"][int(m.group(3))] = tuple(float(m.group(k)) for k in (4, 5, 6))
    if not res:
        raise T.TestFailure("no cable lines in the output:\n" + T.tail(out))
    return res


def irvine(L, L0, EA, w):
    """Horizontal force and midspan sag of an elastic catenary, supports at one level (Irvine 1981)."""
    W = w * L0
    f = lambda H: H * L0 / EA + 2 * H / w * math.asinh(W / (2 * H)) - L  # noqa: E731
    a, b = 1e-6, 1e9
    for _ in range(200):
        m = 0.5 * (a + b)
        a, b = (a, m) if f(m) > 0 else (m, b)
    H = 0.5 * (a + b)
    return H, W * L0 / (8 * EA) + H / w * (math.sqrt(1 + (W / (2 * H)) ** 2) - 1)


def test(etfe, chk):
    with scratch_dir("etfe-cables") as tmp:
        # --- Straight cable: 10 segments, 1000 mm, EA 1e5 N, pulled by 1000 N at its end.
        strip = os.path.join(tmp, "strip.msh")
        cable_meshes.strip(strip, 1000.0, 100.0, 10)
        pull = FILM + ["-mesh_file", strip, "-bc_far_fix", "xyz", "-bc_anchor_fix", "xyz", "-bc_end_force", "1000,0,0",
                       "-cable_cable_EA", 1e5, "-load_increments", 4]
        _, out1 = run(etfe, pull)
        c1 = cables(out1)["cable"]
        lam = 1.01
        for _ in range(50):  # lam (lam^2 - 1) / 2 = N / EA by Newton
            lam -= (lam * (lam * lam - 1) / 2 - 0.01) / ((3 * lam * lam - 1) / 2)
        chk.less(abs(c1["length"] / (1000.0 * lam) - 1), 1e-6,
                 "straight cable: length %.6f mm against %.6f (EA E l / L0 = P), relative difference"
                 % (c1["length"], 1000 * lam))
        chk.less(abs(c1["max"] / 1000.0 - 1), 1e-5, "straight cable: force %.6e N against the 1000 N pull (the film's "
                                                   "share is what differs), relative difference" % c1["max"])
        _, out2 = run(etfe, pull, np=2)
        c2 = cables(out2)["cable"]
        worst = max(abs(c2[k] - c1[k]) / abs(c1[k]) for k in ("min", "max", "length"))
        chk.less(worst, 1e-9, "straight cable: 2 ranks against 1, largest relative difference of force and length")
        # The increments' work counts the cable's force (FormInternalForce): summed over the run it
        # is the cable's strain energy EA L0 E^2 / 2 (the film's adds ~1e-6 of it; the trapezoid
        # over 4 increments of a stiffening bar ~4e-4).
        hist = os.path.join(tmp, "pull_history.csv")
        run(etfe, pull + ["-structure_history", hist])
        work = sum(float(r["work"]) for r in T.read_history(hist))
        strain = (c1["length"] ** 2 - 1000.0 ** 2) / (2 * 1000.0 ** 2)
        energy = 1e5 * 1000.0 * strain ** 2 / 2
        chk.less(abs(work / energy - 1), 1e-3, "straight cable: the increments' work %.3f N mm against the cable's "
                                               "strain energy %.3f N mm, relative difference" % (work, energy))

        # --- A very stiff cable (EA 1e11 N, 100 mm segments): its forces carry a round-off of
        # EA eps |x| / l ~ 2e-4 N each, above the force tolerance; the cable term's round-off floor
        # lets the convergence test accept the balance it can reach (without it every increment
        # failed its line search until the cut-backs ran out).
        rc, out = run(etfe, FILM + ["-mesh_file", strip, "-bc_far_fix", "xyz", "-bc_anchor_fix", "xyz",
                                    "-bc_end_force", "1000,0,0", "-cable_cable_EA", 1e11, "-cable_cable_prestress", 500,
                                    "-load_increments", 2], expect_fail=None)
        chk.check(rc == 0, "very stiff cable (EA 1e11 N): the run completes (exit %d)%s" % (rc, "" if rc == 0 else "\n" + T.tail(out)))
        if rc == 0:
            c = cables(out)["cable"]
            chk.less(abs(c["max"] / 1000.0 - 1), 1e-6, "very stiff cable: force %.9e N against the 1000 N pull, relative "
                                                      "difference" % c["max"])

        # --- Tension only: the end pushed 5 mm towards the anchor: slack, no force.
        _, out = run(etfe, FILM + ["-mesh_file", strip, "-bc_far_fix", "xyz", "-bc_anchor_fix", "xyz", "-bc_end_ux", -5,
                                   "-bc_end_uy", 0, "-bc_end_uz", 0, "-cable_cable_EA", 1e5, "-load_increments", 2])
        c = cables(out)["cable"]
        chk.check(c["slack"] == 10 and c["max"] == 0.0, "compressed cable: all 10 segments slack, force %g N" % c["max"])
        rx = float(re.search(r"support end reaction = \((\S+),", out).group(1))
        chk.less(abs(rx), 1e-2, "compressed cable: the pushed end's reaction (the nearly stiffless film's only), N")

        # --- Irvine's elastic catenary: 10 m span, 40 segments, EA 2e6 N, prestress 500 N, 10 N/m.
        irv = os.path.join(tmp, "irvine.msh")
        cable_meshes.strip(irv, 10000.0, 500.0, 40)
        EA, T0, w = 2e6, 500.0, 10.0
        cat = FILM + ["-mesh_file", irv, "-bc_far_fix", "xyz", "-bc_anchor_fix", "xyz", "-bc_end_fix", "xyz",
                      "-cable_cable_EA", EA, "-cable_cable_prestress", T0, "-cable_cable_weight", w, "-load_increments", 10]
        full = os.path.join(tmp, "full.h5")
        hist = os.path.join(tmp, "full.csv")
        _, out = run(etfe, cat + ["-output", 1, "-output_file", full, "-structure_history", hist])
        c = cables(out)["cable"]
        step, _, data = T.read_steps(full)[-1]
        force = data.get("cables/force")
        one = data["cables/cable"] == 0 if "cables/cable" in data else None
        chk.check(force is not None and one is not None and len(force[one]) == 40
                  and T.printed_agree("%.6e" % force[one].max(), "%.6e" % c["max"])
                  and T.printed_agree("%.6e" % force[one].min(), "%.6e" % c["min"])
                  and not data["cables/slack"][one].any() and len(data["cables/length"][one]) == 40,
                  "catenary: the results file's last step holds the 40 segment forces, lengths and slack flags, "
                  "as reported")
        row = T.read_history(hist)[-1]
        chk.check(T.printed_agree("%.6e" % float(row["cable_cable_force_max"]), "%.6e" % c["max"]) and
                  row["cable_cable_slack_segments"] == "0.00000000e+00",
                  "catenary: the history CSV's last row has the cable's largest force and no slack segment")
        H0, sag0 = irvine(10000.0, 10000.0 / (1 + T0 / EA), EA, w * 1e-3)
        H = c["pull"][0][0]
        sag = float(re.search(r"structure: largest displacement (\S+) mm", out).group(1))
        chk.less(abs(H / H0 - 1), 1e-3, "catenary: horizontal force %.3f N against Irvine's %.3f N, relative difference"
                 % (H, H0))
        chk.less(abs(sag / sag0 - 1), 1e-3, "catenary: midspan sag %.4f mm against Irvine's %.4f mm, relative difference"
                 % (sag, sag0))
        chk.less(abs(-c["pull"][0][2] - 0.5 * w * 1e-3 * c["cut"]), 0.05,
                 "catenary: each support carries half the cable's weight (N off)")
        # Restart mid-load: stop after 5 increments, restart from the checkpoint, compare.
        part, ck = os.path.join(tmp, "part.h5"), os.path.join(tmp, "ck.h5")
        fails, outr = T.stop_and_restart(etfe, cat + ["-output", 1], part, ck, 5, full)
        chk.check(not fails, "catenary: stopped after 5 of 10 increments and restarted, the results equal the "
                             "uninterrupted run bit for bit%s" % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))
        chk.check(LINE.search(outr) and LINE.search(outr).group(0) == LINE.search(out).group(0),
                  "catenary: the restarted run reports the same cable line")

        # --- Sliding cable over a node held in plan and pulled down by 100 N at 3/10 of the span.
        mid = os.path.join(tmp, "mid.msh")
        cable_meshes.strip(mid, 1000.0, 100.0, 10, points={"mid": [3]})
        pulley = FILM + ["-mesh_file", mid, "-bc_far_fix", "xyz", "-bc_anchor_fix", "xyz", "-bc_end_fix", "xyz",
                         "-bc_mid_fix", "xy", "-bc_mid_force", "0,0,-100", "-cable_cable_EA", 1e5,
                         "-cable_cable_prestress", 200, "-load_increments", 4]
        _, out = run(etfe, pulley + ["-cable_cable_sliding"])
        c = cables(out)["cable"]
        p0, p1 = (math.sqrt(sum(x * x for x in p)) for p in c["pull"])
        chk.check(c["sliding"] and c["min"] == c["max"], "sliding cable: one force along it (%.9e, %.9e N)"
                  % (c["min"], c["max"]))
        chk.less(max(abs(p0 / c["max"] - 1), abs(p1 / c["max"] - 1)), 1e-6,
                 "sliding cable: both end pulls equal the force (%.6f, %.6f, %.6f N), relative difference"
                 % (p0, p1, c["max"]))
        chk.less(abs(-c["pull"][0][2] - c["pull"][1][2] - 100.0), 1e-2, "sliding cable: the ends carry the 100 N, N off")
        _, out2 = run(etfe, pulley + ["-cable_cable_sliding"], np=2)
        c2 = cables(out2)["cable"]
        chk.less(abs(c2["max"] / c["max"] - 1), 1e-9, "sliding cable: 2 ranks against 1, force relative difference")
        _, out = run(etfe, pulley)
        c = cables(out)["cable"]
        chk.check(c["max"] > 2 * c["min"], "the same cable fixed: the short leg pulls harder (%.1f vs %.1f N)"
                  % (c["max"], c["min"]))

        # --- Form finding: 2 m square film, stress 1 MPa x 0.25 mm, edge cables of 500 N: R = T/n = 2000 mm.
        sq, found = os.path.join(tmp, "square.msh"), os.path.join(tmp, "found.msh")
        cable_meshes.square(sq, 2000.0, 20)
        ff = ["-scene", "structure", "-analysis", "formfind", "-mesh_file", sq, "-membrane_thickness", 0.25,
              "-formfind_stress", 1, "-formfind_mesh_control", "false", "-formfind_tol", 1e-6, "-formfind_monitor", 0,
              "-bc_west_fix", "xyz", "-bc_east_fix", "xyz", "-cable_south_EA", 1e5, "-cable_south_prestress", 500,
              "-cable_north_EA", 1e5, "-cable_north_prestress", 500, "-formfind_mesh_out", found, "-output", 0]
        _, out = run(etfe, ff)
        c = cables(out)
        xyz = cable_meshes.read_nodes41(found)
        for name, first in (("south", 0), ("north", 20 * 21)):
            R = fit_circle([xyz[first + i + 1][:2] for i in range(21)])
            chk.less(abs(R / 2000.0 - 1), 2e-3, "form finding: edge %s is a circle of radius %.3f mm against T/n = 2000 mm "
                                                "(20 segments), relative difference" % (name, R))
            chk.less(abs(c[name]["cut"] - c[name]["length"] / (1 + 500.0 / 1e5)), 1e-5,
                     "form finding: cable %s's cut length %.6f mm is l / (1 + T/EA)" % (name, c[name]["cut"]))
            chk.check(c[name]["min"] == 500.0 and c[name]["max"] == 500.0, "form finding: cable %s carries 500 N" % name)

        # --- The four-point sail (options/structure/sail_formfind.opts): each edge's discrete curvature
        # |e_i - e_(i-1)| / mean segment length at every interior cable node against n / T = 1 / 20 m.
        sail = os.path.join(tmp, "sail.msh")
        _, out = run(etfe, ["-options_file", os.path.join(T.OPTIONS, "structure", "sail_formfind.opts"), "-output", 0,
                            "-formfind_monitor", 0, "-formfind_mesh_out", sail])
        xyz = cable_meshes.read_nodes41(sail)
        worst, found_cut = 0.0, {name: c["cut"] for name, c in cables(out).items()}
        for name, c in cables(out).items():
            chain = [xyz[k + 1] for k in chain_nodes(name, 12)]
            for i in range(1, 12):
                a, b, d = chain[i - 1], chain[i], chain[i + 1]
                l1, l2 = math.dist(a, b), math.dist(b, d)
                kappa = math.dist([(b[k] - a[k]) / l1 for k in range(3)], [(d[k] - b[k]) / l2 for k in range(3)]) / (
                    0.5 * (l1 + l2))
                worst = max(worst, abs(kappa * 20000.0 - 1))
        chk.less(worst, 2e-3, "four-point sail: the edges' curvature against n/T (12 segments each), largest relative "
                              "difference")
        # The found surface keeps its 1-D groups (line elements): the loaded sail takes its cables from it.
        corners = sum((["-bc_c%d_fix" % k, "xyz"] for k in range(1, 5)), [])
        ropes = sum((["-cable_edge_%d_EA" % k, 1.2e7, "-cable_edge_%d_prestress" % k, 5000] for k in range(1, 5)), [])
        _, out = run(etfe, ["-scene", "structure", "-mesh_file", sail, "-membrane_thickness", 0.25, "-output", 0,
                            "-structure_self_weight", 1, "-load_increments", 2] + corners + ropes)
        loaded = cables(out)
        chk.check(sorted(loaded) == ["edge_1", "edge_2", "edge_3", "edge_4"] and
                  all(abs(c["cut"] / found_cut[n] - 1) < 1e-6 for n, c in loaded.items()),
                  "the form-found sail's mesh carries its four edge cables into a static run (cut length as found)")

        # --- Bad inputs, each refused by name before the run.
        branch = os.path.join(tmp, "branch.msh")
        cable_meshes.strip(branch, 1000.0, 100.0, 10, lines={"branch": [(i, i + 1) for i in range(10)] + [(5, 16)],
                                                             "pieces": [(0, 1), (1, 2), (5, 6)]})
        base = FILM + ["-mesh_file", branch, "-bc_far_fix", "xyz", "-bc_anchor_fix", "xyz"]
        bad = [(["-cable_cable_EA", 0], r"-cable_cable_EA 0: a cable's axial stiffness must be positive"),
               (["-cable_cable_EA", -5], r"-cable_cable_EA -5: a cable's axial stiffness must be positive"),
               (["-cable_nothere_EA", 1e5], r"-cable_nothere_EA: no such cable option or 1-D group.*\(branch, "
                                            r"cable, far, pieces\)"),
               (["-cable_branch_EA", 1e5], r"cable branch is not one chain: node 5 .* joins 3 of its segments"),
               (["-cable_pieces_EA", 1e5], r"cable pieces is not one connected chain"),
               (["-cable_cable_prestress", 100], r"cable cable: give its axial stiffness -cable_cable_EA"),
               (["-cable_cable_EA", 1e5, "-cable_cable_length", 900, "-cable_cable_prestress", 10],
                r"cable cable: give its stress-free length .* or its prestress .*, not both"),
               (["-cable_cable_EA", 1e5, "-cable_cable_prestress", 2e5],
                r"-cable_cable_prestress 200000: a cable carries tension only")]
        for args, pattern in bad:
            _, out = run(etfe, base + args, expect_fail=True)
            chk.check(re.search(pattern, out), "refused: %s (%s)" % (" ".join(map(str, args)), pattern))
        _, out = run(etfe, ff[:-2] + ["-output", 0, "-cable_west_EA", 1e5, "-cable_west_prestress", 10,
                                      "-cable_west_sliding", "-cable_south_sliding"], expect_fail=True)
        chk.check(re.search(r"sliding cables south and west share node 0 \(tag 1", out) or
                  re.search(r"sliding cables west and south share node 0 \(tag 1", out),
                  "refused: a node on two sliding cables")
        _, out = run(etfe, ["-scene", "structure", "-analysis", "formfind", "-mesh_file", sq, "-bc_west_fix", "xyz",
                            "-bc_east_fix", "xyz", "-output", 0], expect_fail=True)
        chk.check("the film's edge from node 0 (tag 1 in the file, at 0, 0, 0) to node 1 (tag 2 in the file, at 100, 0, "
                  "0) is free (no cable, no support)" in out, "refused: form finding with a free edge, named")


def chain_nodes(edge, n):
    """Node indices along an edge of meshes/sail_4point.msh (meshes/sail_4point.py)."""
    idx = lambda i, j: j * (n + 1) + i  # noqa: E731
    return {"edge_1": [idx(i, 0) for i in range(n + 1)], "edge_2": [idx(n, j) for j in range(n + 1)],
            "edge_3": [idx(n - i, n) for i in range(n + 1)], "edge_4": [idx(0, n - j) for j in range(n + 1)]}[edge]


def fit_circle(pts):
    """Radius of the least-squares (algebraic) circle through plane points."""
    n = len(pts)
    A = [[x, y, 1.0] for x, y in pts]
    b = [-(x * x + y * y) for x, y in pts]
    M = [[sum(A[k][i] * A[k][j] for k in range(n)) for j in range(3)] for i in range(3)]
    v = [sum(A[k][i] * b[k] for k in range(n)) for i in range(3)]
    for c in range(3):
        piv = max(range(c, 3), key=lambda r: abs(M[r][c]))
        M[c], M[piv], v[c], v[piv] = M[piv], M[c], v[piv], v[c]
        for r in range(3):
            if r != c:
                f = M[r][c] / M[c][c]
                M[r] = [M[r][j] - f * M[c][j] for j in range(3)]
                v[r] -= f * v[c]
    D, E, F = (v[i] / M[i][i] for i in range(3))
    return math.sqrt(D * D / 4 + E * E / 4 - F)


T.main(test)
