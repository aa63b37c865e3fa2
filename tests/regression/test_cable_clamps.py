"""Sliding cables through clamps with capstan friction, and over pulleys and saddles (docs/cables.md,
docs/theory.md §14).

* a cable over a saddle at a mast head (a held interior node, -cable_<group>_mu 0.2, wrap 90 deg),
  one end anchored, the other pulled out along its leg: it sticks while T_high / T_low < exp(mu theta)
  (the anchored leg keeps its prestress exactly), then slips with the force ratio on exp(mu theta);
  the end forces against the closed form (a conserved stress-free length split by the capstan
  ratio); the saddle's reported reaction against the support's and the vector sum of the two pulls;
* the same cable without friction: a frictionless pulley, one force, reaction N sqrt(2);
* mu = 0 clamps on a moving node reproduce the frictionless sliding cable (one force to rounding);
  with mu = 0.3 the ratio stays within the limit, and 2 ranks give the same forces;
* a restart mid-load (during slip) gives the uninterrupted run's results bit for bit;
* bad inputs refused by name.
The film under the cable is nearly without stiffness (E = 0.001 MPa).
"""
import math
import os
import re

import etfe_testlib as T
from etfe_testlib import run, scratch_dir
import cable_meshes

FILM = ["-scene", "structure", "-material_type", "elastic", "-material_young", 1e-3, "-material_poisson", 0.3,
        "-membrane_thickness", 0.2, "-output", 0]
CLAMP = re.compile(r"structure: cable (\w+) clamp (\d+) \(node (\d+)\): forces = (\S+), (\S+) N, ratio = (\S+), "
                   r"limit exp\(mu theta\) = (\S+) \(theta = (\S+) rad\), last increment = (\w+), transferred = (\S+) mm")
PULLEY = re.compile(r"structure: cable (\w+) (pulley|saddle) \(node (\d+)\): reaction = \((\S+), (\S+), (\S+)\) N, "
                    r"\|reaction\| = (\S+) N")
FORCE = re.compile(r"structure: cable (\w+) \(\d+ segments, sliding\): force min = (\S+) N, max = (\S+) N")
SUPPORT = r"structure: support %s reaction = \((\S+), (\S+), (\S+)\) N"

EA, T0, MU, DMAX = 1e5, 100.0, 0.2, 1.5


def clamps(out):
    res = [dict(N=(float(m.group(4)), float(m.group(5))), ratio=float(m.group(6)), limit=float(m.group(7)),
                theta=float(m.group(8)), status=m.group(9), transfer=float(m.group(10))) for m in CLAMP.finditer(out)]
    if not res:
        raise T.TestFailure("no clamp lines in the output:\n" + T.tail(out))
    return res


def support(out, group):
    return [float(v) for v in re.search(SUPPORT % group, out).groups()]


def closed_form(delta):
    """End forces (anchored leg A, pulled leg B) of the tent: legs of l = 1000 sqrt(2), leg B longer
    by delta, each cut to l / (1 + T0/EA); stick until N_B = r N_A, then N_B = r N_A with the total
    stress-free length conserved (bisection on leg A's stress-free length)."""
    l = 1000.0 * math.sqrt(2.0)
    L0 = l / (1 + T0 / EA)
    r = math.exp(MU * math.pi / 2)
    nb = EA * ((l + delta) / L0 - 1)
    if nb <= r * T0:
        return T0, nb, False
    a, b = L0 * 0.99, L0 * 1.01
    for _ in range(200):
        m = 0.5 * (a + b)
        g = EA * ((l + delta) / (2 * L0 - m) - 1) - r * EA * (l / m - 1)
        a, b = (a, m) if g > 0 else (m, b)  # g grows with leg A's stress-free length
    m = 0.5 * (a + b)
    return EA * (l / m - 1), EA * ((l + delta) / (2 * L0 - m) - 1), True


def test(etfe, chk):
    with scratch_dir("etfe-clamps") as tmp:
        # --- A tent: anchor (0,0,0), saddle at the mast head (1000,0,1000), end (2000,0,0); the end
        # pulled out along its leg by 1.5 mm over 10 increments.
        tent = os.path.join(tmp, "tent.msh")
        cable_meshes.strip(tent, 2000.0, 100.0, 4, points={"mid": [2]}, z=[0, 500, 1000, 500, 0])
        u = DMAX / math.sqrt(2.0)
        base = FILM + ["-mesh_file", tent, "-bc_far_fix", "xyz", "-bc_anchor_fix", "xyz", "-bc_mid_fix", "xyz",
                       "-bc_end_ux", u, "-bc_end_uy", 0, "-bc_end_uz", -u, "-cable_cable_EA", EA,
                       "-cable_cable_prestress", T0, "-cable_cable_sliding", "-load_increments", 10]
        saddle = base + ["-cable_cable_mu", MU]
        hist = os.path.join(tmp, "saddle.csv")
        full = os.path.join(tmp, "full.h5")
        _, out = run(etfe, saddle + ["-structure_history", hist, "-output", 1, "-output_file", full])
        out_saddle = out
        rows = T.read_history(hist)
        stick = slip = 0
        worst_stick = worst_slip = worst_excess = 0.0
        for k, row in enumerate(rows):
            ratio, limit = float(row["cable_cable_clamp0_ratio"]), float(row["cable_cable_clamp0_limit"])
            moved, status = float(row["cable_cable_clamp0_transfer"]), float(row["cable_cable_clamp0_slip"])
            worst_excess = max(worst_excess, ratio / limit - 1)
            na, nb, slipping = closed_form(DMAX * (k + 1) / len(rows))
            if not slipping:
                stick += 1
                chk.check(status == 0 and moved == 0.0 and ratio < limit,
                          "saddle, increment %d: ratio %.6f below exp(mu theta) = %.6f, sticks (nothing passes)"
                          % (k + 1, ratio, limit))
                worst_stick = max(worst_stick, abs(ratio / (nb / na) - 1))
            else:
                slip += 1
                chk.check(status == 1 and moved > 0, "saddle, increment %d: slips towards the pulled leg" % (k + 1))
                worst_slip = max(worst_slip, abs(ratio / limit - 1))
        chk.check(stick >= 3 and slip >= 3, "saddle: %d increments stick, %d slip (closed form)" % (stick, slip))
        chk.less(worst_stick, 1e-6, "saddle, sticking increments: force ratio against the closed form N_B / T0, "
                                    "largest relative difference")
        chk.less(worst_slip, 1e-6, "saddle, slipping increments: force ratio against exp(mu theta) (current "
                                   "angle), largest relative difference")
        chk.less(worst_excess, 1e-12, "saddle: the force ratio never passes exp(mu theta) (largest excess, relative)")
        c = clamps(out)[0]
        na, nb, _ = closed_form(DMAX)
        chk.less(max(abs(c["N"][0] / na - 1), abs(c["N"][1] / nb - 1)), 1e-6,
                 "saddle, end of the pull: forces %.6f, %.6f N against the closed form %.6f, %.6f N, relative "
                 "difference" % (c["N"][0], c["N"][1], na, nb))
        chk.less(abs(c["ratio"] / math.exp(MU * math.pi / 2) - 1), 1e-5,
                 "saddle: final ratio %.9f against exp(mu pi/2) = %.9f (the legs straight to the film's pull), "
                 "relative difference" % (c["ratio"], math.exp(MU * math.pi / 2)))
        p = PULLEY.search(out)
        R = [float(p.group(k)) for k in (4, 5, 6)]
        S = support(out, "mid")
        chk.check(p.group(2) == "saddle", "the held interior node with friction is reported as a saddle")
        chk.less(max(abs(R[k] + S[k]) for k in range(3)), 1e-3,
                 "saddle reaction (%.4f, %.4f, %.4f) N against the mid support's reaction (the film's share "
                 "differs), N off" % tuple(R))
        chk.less(abs(float(p.group(7)) / math.hypot(*c["N"]) - 1), 1e-6,
                 "saddle: |reaction| against the vector sum of the two pulls at 90 deg, relative difference")

        # --- The same cable without friction: a frictionless pulley at the mast head.
        _, out = run(etfe, base)
        m = FORCE.search(out)
        N = float(m.group(3))
        p = PULLEY.search(out)
        chk.check(p and p.group(2) == "pulley" and m.group(2) == m.group(3),
                  "frictionless pulley: one force (%s, %s N) and a pulley line" % (m.group(2), m.group(3)))
        chk.less(abs(float(p.group(7)) / (N * math.sqrt(2.0)) - 1), 1e-6,
                 "frictionless pulley: |reaction| %.6f N against N sqrt(2) = %.6f N, relative difference"
                 % (float(p.group(7)), N * math.sqrt(2)))

        # --- Restart in the slip phase: stop after 6 of 10 increments, restart, compare.
        part, ck = os.path.join(tmp, "part.h5"), os.path.join(tmp, "ck.h5")
        fails, outr = T.stop_and_restart(etfe, saddle + ["-output", 1], part, ck, 6, full)
        chk.check(not fails, "saddle: stopped after 6 of 10 increments (slipping) and restarted, the results equal the "
                             "uninterrupted run bit for bit%s" % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))
        chk.check(CLAMP.search(outr) and CLAMP.search(outr).group(0) == CLAMP.search(out_saddle).group(0),
                  "saddle: the restarted run reports the same clamp line")

        # --- A clamp on a moving node (held in plan, pulled down 100 N at 3/10 of the span).
        mid = os.path.join(tmp, "mid.msh")
        cable_meshes.strip(mid, 1000.0, 100.0, 10, points={"mid": [3]})
        pull = FILM + ["-mesh_file", mid, "-bc_far_fix", "xyz", "-bc_anchor_fix", "xyz", "-bc_end_fix", "xyz",
                       "-bc_mid_fix", "xy", "-bc_mid_force", "0,0,-100", "-cable_cable_EA", 1e5,
                       "-cable_cable_prestress", 200, "-cable_cable_sliding", "-load_increments", 4]
        forces = []  # the segment forces of the results file's last step: the sliding cable, mu = 0 clamp
        for name, extra in (("sliding", []), ("mu0", ["-cable_cable_clamps", "mid", "-cable_cable_mu", 0])):
            h5 = os.path.join(tmp, name + ".h5")
            run(etfe, pull + extra + ["-output", 1, "-output_file", h5])
            forces.append(T.read_steps(h5)[-1][2]["cables/force"])
        ref, f0 = forces
        chk.less((f0.max() - f0.min()) / f0.max(), 1e-12, "mu = 0 clamp: one force over the 10 segments (%.15e to "
                                                           "%.15e N), relative spread" % (f0.min(), f0.max()))
        chk.less(abs(f0.max() / ref.max() - 1), 1e-9, "mu = 0 clamp against the frictionless sliding cable's force "
                                                      "%.12e N, relative difference" % ref.max())
        _, out1 = run(etfe, pull + ["-cable_cable_clamps", "mid", "-cable_cable_mu", 0.3])
        c1 = clamps(out1)[0]
        chk.check(c1["status"] == "slip" and c1["ratio"] <= c1["limit"] * (1 + 1e-12),
                  "mu = 0.3 clamp on the moving node: slips, ratio %.9f within exp(mu theta) = %.9f"
                  % (c1["ratio"], c1["limit"]))
        _, out2 = run(etfe, pull + ["-cable_cable_clamps", "mid", "-cable_cable_mu", 0.3], np=2)
        c2 = clamps(out2)[0]
        scale = max(c1["N"])
        chk.less(max(abs(c2["N"][k] - c1["N"][k]) for k in range(2)) / scale, 1e-9,
                 "mu = 0.3 clamp: 2 ranks against 1, largest force difference over the force scale %.3f N" % scale)

        # --- Bad inputs, each refused by name before the run.
        fixed = pull[:pull.index("-cable_cable_sliding")] + ["-load_increments", 1]
        bad = [(["-cable_cable_sliding", "-cable_cable_clamps", "far"],
                r"-cable_cable_clamps far: node 11 .* is not on cable cable"),
               (["-cable_cable_sliding", "-cable_cable_clamps", "anchor"],
                r"-cable_cable_clamps anchor: node 0 .* is an end of cable cable"),
               (["-cable_cable_sliding", "-cable_cable_clamps", "nothere"],
                r"-cable_cable_clamps nothere: no node group nothere in the mesh"),
               (["-cable_cable_sliding", "-cable_cable_mu", -0.1],
                r"-cable_cable_mu -0.1: a friction coefficient is not negative"),
               (["-cable_cable_clamps", "mid"], r"cable cable: clamps and friction .* act on a sliding cable"),
               (["-cable_cable_sliding", "-cable_cable_mu", 0.2], r"-cable_cable_mu: cable cable has no clamp and no "
                                                                  r"saddle")]
        for args, pattern in bad:
            _, out = run(etfe, fixed + args, expect_fail=True)
            chk.check(re.search(pattern, out), "refused: %s (%s)" % (" ".join(map(str, args)), pattern))

T.main(test)
