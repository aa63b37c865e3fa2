#!/usr/bin/python3
"""An increment is accepted only where the forces balance, whatever SNES's own tests say.

SNES's relative tests (|R| <= -snes_rtol |R0|, a step small against |x|) only propose convergence:
a first residual made huge by a wild start, or a loose -snes_rtol, would otherwise pass them far
above the load stepper's force tolerance (-load_force_rtol of the reactions and loads). Measured on
Hencky's membrane (options/hencky.opts, 5 increments) with -snes_rtol 0.5 before the fix: every
increment accepted after 1-2 Newton iterations at |R| = 9-56 N, centre deflection 26.748 mm (3.1 %
from the closed form; 25.956 mm converged).

Asserted: with -snes_rtol 0.5 every increment ends at |R| below 1e-6 N (the force tolerance here is
~1e-10 of ~10^3 N) and the centre deflection equals the default run's in every printed digit.

Also: the tangent predictor (-load_tangent_predictor) on a start whose tangent is singular (a flat
film without prestress, free out of its plane) keeps the plain predictor; before, MUMPS's failed
factorization stopped the run in its solve phase (INFOG(1) = -3).
"""
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402


def deflection(out):
    return T.scene_value(out, "hencky", "centre_deflection")


def test(etfe, chk):
    base = ["-options_file", T.opts("hencky"), "-output", "0", "-load_monitor", "1"]
    _, ref = T.run(etfe, base)
    _, loose = T.run(etfe, base + ["-snes_rtol", "0.5"])
    incs = T.increments(loose)
    chk.check(len(incs) == 5, "-snes_rtol 0.5: 5 increments printed (%d)" % len(incs))
    worst = max(i["residual"] for i in incs) if incs else float("inf")
    chk.check(worst < 1e-6, "-snes_rtol 0.5: every increment accepted in force balance (largest |R| %.3g N)" % worst)
    w, w0 = deflection(loose), deflection(ref)
    chk.check(w == w0,
              "-snes_rtol 0.5: centre deflection %.9g mm equals the default run's %.9g mm" % (w, w0))

    # A flat, unstressed square stretched in its plane, free in z: the first tangent is singular.
    flat = ["-scene", "structure", "-structure_mesh_generator", "rectangle", "-structure_mesh_size", "3000,3000",
            "-mesh_nx", 8, "-mesh_ny", 8, "-membrane_thickness", 0.25, "-material_type", "elastic",
            "-material_young", 800, "-material_poisson", 0.43, "-load_increments", 2, "-output", 0]
    for g in ("left", "right", "bottom", "top"):
        flat += ["-bc_%s_gradient" % g, "0.0015,0,0,0.0015", "-bc_%s_fix" % g, "z"]
    _, plain = T.run(etfe, flat)
    rc, pred = T.run(etfe, flat + ["-load_tangent_predictor"], expect_fail=None)
    chk.check(rc == 0, "tangent predictor on a singular first tangent: the run completes (exit %d)%s"
              % (rc, "" if rc == 0 else "\n" + T.tail(pred)))
    if rc == 0:
        largest = lambda out: float(re.search(r"structure: largest displacement (\S+) mm", out).group(1))  # noqa: E731
        chk.less(abs(largest(pred) / largest(plain) - 1), 1e-9,
                 "tangent predictor on a singular first tangent: largest displacement %.6f mm against %.6f mm without "
                 "it, relative difference" % (largest(pred), largest(plain)))


T.main(test)
