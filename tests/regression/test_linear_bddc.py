#!/usr/bin/python3
"""Domain decomposition gives Newton's answer: Hencky (options/hencky.opts, 24 rings) on 2 ranks
with GMRES + PCBDDC on the unassembled tangent (options/solvers/gmres_bddc.opts) against the
direct default (MUMPS): the same Newton iterations, the final displacement within 1e-8 relative,
the printed centre deflection equal, and at most 30 Krylov iterations per solve (9-13 measured).
The sealed two-layer cushion (gas chambers: the rank-one term around the unassembled tangent)
gives MUMPS's history to 1e-9. -pc_type bddc alone takes the unassembled matrix; with an
assembled one it is refused."""
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

RE_KSP = re.compile(r"Linear solve converged due to \S+ iterations (\d+)")


def main_test(etfe, chk):
    with T.scratch_dir("bddc") as tmp:
        runs = {}
        for name, extra in (("mumps", []),
                            ("bddc", ["-options_file", "options/solvers/gmres_bddc.opts", "-ksp_converged_reason"])):
            h5 = os.path.join(tmp, name + ".h5")
            rc, out = T.run(etfe, ["-options_file", T.opts("hencky"), "-output_file", h5] + extra, np=2)
            chk.check(T.status(h5) == "complete", "%s: results status 'complete'" % name)
            runs[name] = (h5, out, T.summary(out))
        (h0, o0, s0), (h1, o1, s1) = runs["mumps"], runs["bddc"]
        chk.check("KSP gmres, PC bddc" in o1, "the run names GMRES + BDDC")
        its = [int(m.group(1)) for m in RE_KSP.finditer(o1)]
        print("bddc: %d solves, Krylov iterations per solve %s; Newton %d (MUMPS %d)" %
              (len(its), sorted(set(its)), s1["newton"], s0["newton"]))
        chk.check(len(its) >= s1["newton"], "every Newton iteration solved with GMRES (%d solves)" % len(its))
        chk.less(max(its or [1000]), 30, "largest Krylov iterations per solve")
        chk.check(s1["newton"] == s0["newton"], "Newton iterations %d, MUMPS %d" % (s1["newton"], s0["newton"]))
        f, rows = T.h5compare.compare_rows(h1, h0, step="last", fields={"displacement": (1e-8, 0.0)}, only=True)
        print(T.h5compare.format_table(rows))
        chk.check(not f and rows, "final displacement within 1e-8 relative of MUMPS's%s" % ("" if not f else ": " + "; ".join(f)))
        a = T.scene_value(o0, "hencky", "centre_deflection")
        b = T.scene_value(o1, "hencky", "centre_deflection")
        chk.check(a is not None and a == b, "printed centre deflection: MUMPS %s, BDDC %s" % (a, b))

        # A sealed cushion: the gas's rank-one term wraps the unassembled tangent as it does the
        # assembled one (BDDC preconditions the sparse part): MUMPS's history.
        hist = {}
        for name, extra in (("mumps", []), ("bddc", ["-options_file", "options/solvers/gmres_bddc.opts"])):
            hist[name] = os.path.join(tmp, "cushion_%s.csv" % name)
            T.run(etfe, ["-options_file", T.opts("cushion/hexagon_2layer"), "-output", 0, "-output_file",
                         os.path.join(tmp, "cushion_%s.h5" % name), "-structure_history", hist[name]] + extra, np=2)
        worst, where = T.largest_family_difference(T.read_history(hist["mumps"]), T.read_history(hist["bddc"]))
        chk.less(worst, 1e-9, "sealed two-layer cushion, BDDC against MUMPS on 2 ranks (at %s)" % (where,))

        rc, out = T.run(etfe, ["-options_file", T.opts("hencky"), "-output", 0, "-output_file",
                               os.path.join(tmp, "refused.h5"), "-pc_type", "bddc", "-mat_type", "aij"],
                        np=2, expect_fail=True)
        chk.check("-pc_type bddc needs the unassembled tangent" in out, "bddc on an assembled matrix is refused by name")


if __name__ == "__main__":
    T.main(main_test)
