#!/usr/bin/python3
"""Bad mesh files (tests/regression/badmesh_cases.py): each is refused with a message naming the
file and the defect, or, where the repair is unambiguous (orientation, quadrangles), repaired with
a note and then solved right: the patch test's closed form holds on the repaired mesh. Also: the
patch scene strains a mesh file by the mesh's own size, not by -patch_lx."""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402
import badmesh_cases  # noqa: E402


def main_test(etfe, chk):
    with T.scratch_dir("badmesh") as tmp:
        for k, (name, argv, expect, ok) in enumerate(badmesh_cases.cases(tmp)):
            h5 = os.path.join(tmp, "case%02d.h5" % k)
            rc, out = T.run(etfe, argv + ["-output_file", h5, "-load_monitor", "0"], expect_fail=None,
                            timeout=60)
            shown = T.error_message(out) if rc != 0 else out
            first = next((l for l in shown.splitlines() if expect in l), shown.splitlines()[0] if shown else "")
            if not chk.check((rc == 0) == ok, "%s: exit code %d (%s)" % (name, rc, "zero" if ok else "non-zero")):
                print("    output tail:\n" + T.tail(out, 6))
                continue
            chk.check(expect in out, "%s: output says %r: %s" % (name, expect, first.strip()[:160]))
            mesh_path = argv[argv.index("-mesh_file") + 1]
            if not ok:
                chk.check(mesh_path in T.error_message(out), "%s: the message names the file" % name)
                st = T.status(h5) if os.path.exists(h5) else None
                chk.check(st != "complete", "%s: no results file with status 'complete'" % name)
            else:
                err = T.scene_value(out, "patch", "closed_form", "relative_error")
                chk.less(err, 1e-9, "%s: the patch test holds on the repaired mesh (closed-form error)" % name)

        # A 10 x 10 mm mesh with the patch options of a 1000 mm patch: the 2 % strain applies to
        # the mesh's 10 mm (before: a displacement of 2 % of -patch_lx = 20 mm, 200 % strain).
        small = os.path.join(tmp, "small_square.msh")
        badmesh_cases.write_msh(small, badmesh_cases.grid_nodes(10.0), badmesh_cases.grid_triangles())
        rc, out = T.run(etfe, ["-options_file", badmesh_cases.PATCH_OPTS, "-mesh_file", small,
                               "-output_file", os.path.join(tmp, "small.h5"), "-load_monitor", "0"])
        chk.check("spans 10 x 10 mm" in out, "10 mm mesh: the scene says it uses the mesh's size")
        chk.less(T.scene_value(out, "patch", "closed_form", "relative_error"), 1e-9,
                 "10 mm mesh with -patch_lx 1000: closed-form error")


if __name__ == "__main__":
    T.main(main_test)
