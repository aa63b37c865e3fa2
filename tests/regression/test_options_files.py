#!/usr/bin/python3
"""A user's options file outside the checkout includes the shipped solver files as the shipped
cases do ("-options_file options/solvers/mumps_lu.opts"), from any working folder; a missing
include names every path tried."""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test(etfe, chk):
    etfe = os.path.abspath(etfe)
    with T.scratch_dir("options-files") as tmp:
        case, bad, elsewhere = (os.path.join(tmp, n) for n in ("case.opts", "bad.opts", "elsewhere"))
        os.makedirs(elsewhere)
        with open(case, "w") as f:
            f.write("# a user's case beside no checkout\n-scene hencky\n-hencky_radius 500\n-hencky_pressure 2e-4\n"
                    "-membrane_thickness 0.25\n-material_type elastic\n-mesh_rings 8\n-load_increments 2\n"
                    "-options_file options/solvers/mumps_lu.opts\n")
        with open(bad, "w") as f:
            f.write("-scene hencky\n-options_file options/solvers/no_such_solver.opts\n")
        rc, out = T.run(etfe, ["-options_file", case, "-output", "0", "-load_monitor", "0"], cwd=elsewhere,
                        expect_fail=None)
        ok = rc == 0 and "hencky: centre_deflection" in out and "PC lu mumps" in out
        chk.check(ok, "a file in %s includes options/solvers/mumps_lu.opts from the product's folder (rc %d)%s"
                  % (tmp, rc, "" if ok else ": " + T.tail(out)))
        rc, out = T.run(etfe, ["-options_file", bad, "-output", "0"], cwd=elsewhere, expect_fail=True)
        want = [os.path.join(tmp, "options/solvers/no_such_solver.opts"),
                os.path.join(elsewhere, "options/solvers/no_such_solver.opts"),
                os.path.join(REPO, "options/solvers/no_such_solver.opts")]
        ok = "bad.opts:2" in out and "no such file" in out and all(w in out for w in want)
        chk.check(ok, "a missing include names the file, its line and every path tried%s" % ("" if ok else ": " + T.tail(out)))


T.main(test)
