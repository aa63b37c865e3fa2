#!/usr/bin/python3
"""Annulus under torsion with the tension-field membrane (options/annulus.opts): a
pretensioned annulus (a = 100, b = 500 mm, eps0 = 1e-4) whose rigid hub turns by 5e-4 rad, about
twice the wrinkling onset. Against the closed form (Stein & Hedgepeth 1961 / Mikulas 1964 for
these boundary conditions, src/verification/annulus_closed_form.cpp):
(a) on 8 x 48 and 32 x 192 elements (rings x sectors) the errors of the wrinkled zone's radius,
    the hub rotation (closed form at the film's torque) and the torque fall with refinement, and
    on 32 x 192 each is within 2 % (measured 0.08 %, 1.4 %, 1.0 %);
(b) the wrinkled zone is wrinkled, not slack, and wrinkle_state / wrinkle_dir are written;
(c) bad input: a negative pretension, and a rotation that leaves the film around the hub slack
    (no partly wrinkled state), stop with a message naming the option.
"""
import os
import sys

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

MESHES = [(8, 48), (32, 192)]
QUANTITIES = ("wrinkle_radius", "hub_rotation", "torque")


def main_test(etfe, chk):
    errs = {}
    with T.scratch_dir("wrinkle_annulus") as tmp:
        for nr, nt in MESHES:
            h5 = os.path.join(tmp, "annulus_%d.h5" % nr)
            _, out = T.run(etfe, ["-options_file", T.opts("annulus"), "-mesh_rings", nr, "-mesh_sectors", nt,
                                  "-output_file", h5, "-load_monitor", "0"])
            errs[nr] = {q: T.scene_value(out, "annulus", q, "relative_error") for q in QUANTITIES}
            vals = {q: T.scene_value(out, "annulus", q) for q in QUANTITIES}
            print("%3d x %3d: " % (nr, nt) + ", ".join("%s = %.6e (error %.3e)" % (q, vals[q], errs[nr][q])
                                                      for q in QUANTITIES) + ", %.1f s" % T.run.last_wall)
            d = T.read_steps(h5)[-1][2]
            st = d["wrinkle_state"]
            chk.check(np.any(st == 1) and not np.any(st == 2), "%dx%d: wrinkled elements, none slack (states %s)"
                      % (nr, nt, np.unique(st)))
            wd = d["wrinkle_dir"][st == 1]
            chk.less(float(np.abs(np.linalg.norm(wd, axis=1) - 1).max()), 1e-12,
                     "%dx%d: wrinkle_dir unit vectors in the wrinkled zone" % (nr, nt))
        coarse, fine = errs[MESHES[0][0]], errs[MESHES[-1][0]]
        for q in QUANTITIES:
            chk.less(fine[q], coarse[q], "%s error falls with refinement (%.3e -> %.3e)" % (q, coarse[q], fine[q]))
            chk.less(fine[q], 0.02, "%s within 2 %% on %d x %d" % (q, MESHES[-1][0], MESHES[-1][1]))

        for args, words in (
                (["-annulus_pretension_strain", "-1e-4"], ["-annulus_pretension_strain", "positive pretension"]),
                (["-annulus_rotation", "0.01"], ["-annulus_rotation", "slack"])):
            _, out = T.run(etfe, ["-options_file", T.opts("annulus"), "-output", "0"] + args, expect_fail=True)
            msg = T.error_message(out)
            print("refused %s: %s" % (" ".join(args), msg.splitlines()[0] if msg else "(no message)"))
            for w in words:
                chk.check(w in msg, "%s: message names %r" % (" ".join(args), w))


if __name__ == "__main__":
    T.main(main_test)
