"""A friction coefficient per rigid support (-contact_<support>_mu) in the general scene.

Two sheets 200 x 100 mm side by side in one mesh, each on a table of its own (plane supports ta and
tb, both the plane z = 0: each takes the nodes of its -rigid_<name>_nodes group), pressed on by
0.5 kPa and pulled by their edges until they slide, as the one-table check of
test_structure_scenes.py: each pull equals its own table's mu times the normal force on its pairs
(the pressure on the sheet less what the held edge takes itself, its reaction Z), within 1e-3, with
ta at -contact_mu 0.3 and tb at -contact_tb_mu 0.6. Refused by name: a coefficient of a support
the scene does not have, and a negative one. A law per support (-contact_<support>_friction): tb
frictionless (none) beside ta at 0.3 slides at no force; with the set's law none and tb's own
implicit, tb slides at -contact_mu 0.3 times its normal force and ta at none. Refused: a law of a
support the scene does not have, and an unknown law.
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

    # A law per support (-contact_<support>_friction): tb frictionless beside ta's friction, and the
    # reverse, with the set's law none and tb's own implicit (tb then at -contact_mu as given).
    def pulls(args, name):
        path = os.path.join(tmp, name + ".csv")
        run(etfe, base + args + ["-structure_history", path])
        last = read_history(path)[-1]
        return [(float(last["%s_right_RX" % s]), Q * 1e-3 * L * W - float(last["%s_right_RZ" % s])) for s in "ab"]
    (ta, na), (tb, nb) = pulls(["-contact_tb_friction", "none"], "tb_none")
    chk.check(abs(ta - 0.3 * na) < 1e-3 * 0.3 * na and abs(tb) < 1e-6 * ta,
              "-contact_tb_friction none: sheet a slides at %.4f N = 0.3 x %.4f N, sheet b on its frictionless table "
              "at %.2e N" % (ta, na, tb))
    (ta, na), (tb, nb) = pulls(["-contact_friction", "none", "-contact_tb_friction", "implicit"], "ta_none")
    chk.check(abs(tb - 0.3 * nb) < 1e-3 * 0.3 * nb and abs(ta) < 1e-6 * tb,
              "-contact_friction none -contact_tb_friction implicit: sheet b slides at %.4f N = -contact_mu 0.3 x "
              "%.4f N, sheet a at %.2e N" % (tb, nb, ta))

    refusals = [
        (["-contact_tc_friction", "none"], r"-contact_tc_friction: no such rigid support.*\(ta, tb\)"),
        (["-contact_tb_friction", "rubber"], r"-contact_tb_friction: \"rubber\" \(entry 1\) is not a friction law"),
        (["-contact_tc_mu", 0.5], r"-contact_tc_mu: no such rigid support.*\(ta, tb\)"),
        (["-contact_tb_mu", -0.1], r"-contact_tb_mu -0\.1: the friction coefficient must be >= 0"),
    ]
    for args, pattern in refusals:
        rc, out = run(etfe, base + args, expect_fail=True)
        chk.check(re.search(pattern, out, re.S) is not None, "refused: %s -> /%s/" % (" ".join(map(str, args)), pattern))
chk.finish()
