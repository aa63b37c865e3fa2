"""The front door: PETSc users' habits work, typos of this project's options stop a
run with the closest name, options that exist but are not used by the chosen configuration only
warn, -help is the manual, options files do not depend on the current folder and a bad line in
one is one message naming file and line."""
import os

from etfe_testlib import Checker, etfe_path, opts, run, scratch_dir

etfe = etfe_path()
chk = Checker("badinput_options")
patch = ["-options_file", opts("patch"), "-output", 0, "-load_monitor", 0]

rc, out = run(etfe, patch + ["-snes_converged_reason", "-ksp_converged_reason", "-options_view"])
chk.check(rc == 0 and "Nonlinear solve converged" in out and "#PETSc Option Table entries" in out,
          "PETSc's -snes_converged_reason, -ksp_converged_reason and -options_view work")

rc, out = run(etfe, patch + ["-material_younq", 800], expect_fail=True)
chk.check("unknown option(s): -material_younq (did you mean -material_young?)" in out,
          "a typo of this project's option stops the run and names the closest option")

rc, out = run(etfe, patch + ["-material_type", "elastic", "-material_yield", "10,20"])
chk.check(rc == 0 and "not used by this configuration: -material_yield" in out,
          "an option this project knows but the configuration does not use warns, the run goes on")

rc, out = run(etfe, ["-help"])
for word in ("-contact_friction", "-contact_kn", "-analysis", "-etfe_traceback", "-options_allow_unused",
             "13.28,23.04", "-saddle_draw_d", "-load_increments"):
    chk.check(word in out, "-help without an options file lists %s" % word)

rc, out = run(etfe, ["-options_file", opts("hencky"), "-mesh_rings", "abc"], expect_fail=True)
chk.check("the value of -mesh_rings" in out, "a value of the wrong type names its option")

rc, out = run(etfe, ["-scene_list"])
chk.check(all(s in out for s in ("hencky", "capstan", "saddle", "options/capstan.opts")),
          "-scene_list says what each scene computes and names its options files")

with scratch_dir() as tmp:
    rc, out = run(etfe, ["-options_file", os.path.abspath(opts("patch")), "-output", "0", "-load_monitor", "0"],
                  cwd=tmp, expect_fail=None)
    chk.check(rc == 0 and "patch:" in out, "an options file (with its -options_file includes) runs from another folder")
    bad = os.path.join(tmp, "bad.opts")
    with open(bad, "w") as f:
        f.write("# a case\n-options_file %s\nmesh_nx 8\n" % os.path.abspath(opts("patch")))
    rc, out = run(etfe, ["-options_file", bad], cwd=tmp, expect_fail=None)
    msg = out.strip()
    chk.check(rc != 0 and msg.startswith("etfe: %s:3:" % bad) and len(msg.splitlines()) == 1
              and "MPI_ABORT" not in msg, "a bad options-file line is one message naming file:line (%s)" % msg[:80])
chk.finish()
