"""The LU package by size (options/solvers/lu.opts, -etfe_lu_native_max_dof 5000 in the saddle
cases): DD1511 at the thesis density on one rank is factored with PETSc's own LU, on two ranks and
with -etfe_lu_native_max_dof 0 or -pc_factor_mat_solver_type mumps with MUMPS; every run takes the
same Newton iterations and part A/B Mises and the five slides of every increment agree to 1e-9 of
each quantity's largest value (the packages differ only in round-off)."""

from etfe_testlib import dd1511_case, form_found_saddle, increments, largest_history_difference, main, scratch_dir

COLUMNS = ["A_mises", "B_mises"] + ["slide%d_%s" % (i, c) for i in range(1, 6) for c in "XY"]


def test(etfe, chk):
    with scratch_dir() as tmp:
        msh = form_found_saddle(etfe, tmp)

        def case(name, extra, np=1):
            out, history = dd1511_case(etfe, msh, tmp, name, ["-load_increments", 40] + extra, np=np)
            package = "petsc" if "PC lu petsc" in out else "mumps" if "PC lu mumps" in out else "?"
            its = [i["newton"] for i in increments(out)]
            print("%-12s ranks %d, package %s, Newton %d" % (name, np, package, sum(its)))
            return package, its, history

        pkg0, its0, h0 = case("default", [])
        chk.check(pkg0 == "petsc", "one rank, 2 340 DOF: PETSc's own LU (got %s)" % pkg0)
        chk.check(len(h0) == 40, "default: %d history rows of 40" % len(h0))
        for name, extra, np, want in (("max_dof_0", ["-etfe_lu_native_max_dof", 0], 1, "mumps"),
                                      ("named_mumps", ["-pc_factor_mat_solver_type", "mumps"], 1, "mumps"),
                                      ("two_ranks", [], 2, "mumps")):
            pkg, its, h = case(name, extra, np)
            chk.check(pkg == want, "%s: package %s (expected %s)" % (name, pkg, want))
            chk.check(its == its0, "%s: the same Newton iterations per increment (%d vs %d in all)"
                      % (name, sum(its), sum(its0)))
            chk.check(len(h) == len(h0), "%s: %d history rows" % (name, len(h)))
            worst, where = largest_history_difference(h0, h, COLUMNS)
            chk.less(worst, 1e-9, "%s: largest difference from PETSc's LU (at step/column %s)" % (name, where))


main(test)
