#!/usr/bin/python3
"""Options nobody reads are refused before the run, not reported after it:
  * an option whose first word neither this program nor PETSc uses (-tendon_edge_1_EA) stops the
    run before it computes (no increment, no results file), naming it; a misspelt first word gets
    the closest known name (-snse_rtol: -snes_rtol, -materal_young: -material_young);
  * PETSc's options of many families still pass (-snes_, -sub_, -mg_levels_, -fieldsplit_0_,
    -petscspace_, -flatten_ (this program's prefix for a PETSc solver), -on_error_, -no_): the run
    completes and those nothing read are only warned about at its end;
  * -options_allow_unused still accepts an unknown one;
  * -mat_mumps_icntl_14, which the automatic LU choice sets itself, is not reported as never used
    by a run in which MUMPS never factors (every increment converged without a Newton step), nor
    when options/solvers/mumps_lu.opts set it and PETSc's own LU is asked for.
"""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

PATCH = ["-options_file", T.opts("patch")]


def refused(etfe, chk, tmp, extra, name, hint):
    h5 = os.path.join(tmp, "refused.h5")
    rc, out = T.run(etfe, PATCH + extra + ["-output_file", h5], expect_fail=None)
    msg = T.error_message(out) or T.tail(out, 3)
    ok = rc != 0 and not T.increments(out) and not os.path.exists(h5) and name in msg and \
        "neither this program nor PETSc" in msg and (hint is None or ("did you mean %s?" % hint) in msg)
    chk.check(ok, "%s refused before the run (exit %d, %d increments%s): %s" % (
        " ".join(str(x) for x in extra), rc, len(T.increments(out)), ", hint " + hint if hint else "", msg))


def main_test(etfe, chk):
    with T.scratch_dir("options_unknown") as tmp:
        refused(etfe, chk, tmp, ["-tendon_edge_1_EA", 5], "-tendon_edge_1_EA", None)
        refused(etfe, chk, tmp, ["-snse_rtol", "1e-9"], "-snse_rtol", "-snes_rtol")
        refused(etfe, chk, tmp, ["-materal_young", 800], "-materal_young", "-material_young")
        refused(etfe, chk, tmp, ["-kps_type", "preonly"], "-kps_type", "-ksp_type")

        petsc = ["-snes_rtol", "1e-9", "-sub_pc_type", "ilu", "-mg_levels_ksp_type", "gmres",
                 "-fieldsplit_0_ksp_type", "preonly", "-petscspace_degree", 1, "-flatten_ksp_type", "preonly",
                 "-on_error_abort", "-no_signal_handler"]
        rc, out = T.run(etfe, PATCH + petsc + ["-output", 0], expect_fail=None)
        warn = [l for l in out.splitlines() if "never used" in l]
        chk.check(rc == 0 and len(T.increments(out)) == 2 and warn and
                  all(n in warn[0] for n in ("-sub_pc_type", "-mg_levels_ksp_type", "-petscspace_degree")),
                  "PETSc's option families pass the check; those nothing read are warned about at the end: %s"
                  % (warn[:1] or T.tail(out, 2)))

        rc, out = T.run(etfe, PATCH + ["-tendon_edge_1_EA", 5, "-options_allow_unused", "-output", 0], expect_fail=None)
        chk.check(rc == 0 and len(T.increments(out)) == 2, "-options_allow_unused accepts -tendon_edge_1_EA (exit %d)" % rc)

        rc, out = T.run(etfe, ["-scene", "patch", "-patch_strain_x", 0, "-output", 0], expect_fail=None)
        never = [l for l in out.splitlines() if "never used" in l]
        chk.check(rc == 0 and not never, "a patch that needs no Newton step (strain 0, the automatic LU choice): no "
                  "option reported never used %s" % never)
        rc, out = T.run(etfe, PATCH + ["-pc_factor_mat_solver_type", "petsc", "-output", 0], expect_fail=None)
        never = [l for l in out.splitlines() if "never used" in l]
        chk.check(rc == 0 and not never, "mumps_lu.opts's -mat_mumps_icntl_14 with PETSc's own LU asked for: not "
                  "reported never used %s" % never)


if __name__ == "__main__":
    T.main(main_test)
