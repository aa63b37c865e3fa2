"""A friction coefficient per rigid support (-contact_<support>_mu) in the general scene.

Two sheets 200 x 100 mm side by side in one mesh, each on a table of its own (plane supports ta and
tb, both the plane z = 0: each takes the nodes of its -rigid_<name>_nodes group), pressed on by
0.5 kPa and pulled by their edges until they slide, as the one-table check of
test_structure_scenes.py: each pull equals its own table's mu times the normal force on its pairs
(the pressure on the sheet less what the held edge takes itself, its reaction Z), within 1e-3, with
ta at -contact_mu 0.3 and tb at -contact_tb_mu 0.6. Refused by name: a coefficient of a support
the scene does not have, and a negative one.
"""
import os
import re

from etfe_testlib import Checker, etfe_path, read_history, run, scratch_dir
import group_meshes

etfe = etfe_path()
chk = Checker("structure_support_friction")
L, W, Q = 200.0, 100.0, 0.5  # mm, mm, kPa

with scratch_dir() as tmp:
    msh = os.path.join(tmp, "two.msh")
    group_meshes.two_sheets(msh, L, W, 8, 4, 50.0)
    base = ["-scene", "structure", "-mesh_file", msh, "-material_type", "elastic", "-material_young", 800,
            "-material_poisson", 0.43, "-structure_rigid", "ta,tb", "-contact_friction", "implicit",
            "-contact_mu", 0.3, "-contact_frictionless_until", 1, "-film_all_pressure", "%g,%g" % (-Q, -Q),
            "-load_increments", 40, "-load_monitor", 0, "-output", 0]
    for t, nodes in (("ta", "a_nodes"), ("tb", "b_nodes")):
        base += ["-rigid_%s_type" % t, "plane", "-rigid_%s_centre" % t, "0,0,0", "-rigid_%s_axis" % t, "0,0,1",
                 "-rigid_%s_nodes" % t, nodes]
    for s in ("a", "b"):
        base += ["-bc_%s_right_ux" % s, "0,2", "-bc_%s_right_fix" % s, "yz"]

    hist = os.path.join(tmp, "two.csv")
    rc, out = run(etfe, base + ["-contact_tb_mu", 0.6, "-structure_history", hist])
    h = read_history(hist)
    chk.check("friction coefficient per support (-contact_<support>_mu): ta 0.3, tb 0.6" in out,
              "the set-up names each support's coefficient")
    for s, mu in (("a", 0.3), ("b", 0.6)):
        pull, held = float(h[-1]["%s_right_RX" % s]), float(h[-1]["%s_right_RZ" % s])
        expect = mu * (Q * 1e-3 * L * W - held)
        chk.less(abs(pull - expect) / expect, 1e-3, "sheet %s on t%s slides at T = %.4f N, mu (q A - R_z) = %.4f N "
                                                    "(mu %.1f), relative difference" % (s, s, pull, expect, mu))

    refusals = [
        (["-contact_tc_mu", 0.5], r"-contact_tc_mu: no such rigid support.*\(ta, tb\)"),
        (["-contact_tb_mu", -0.1], r"-contact_tb_mu -0\.1: the friction coefficient must be >= 0"),
    ]
    for args, pattern in refusals:
        rc, out = run(etfe, base + args, expect_fail=True)
        chk.check(re.search(pattern, out, re.S) is not None, "refused: %s -> /%s/" % (" ".join(map(str, args)), pattern))
chk.finish()
